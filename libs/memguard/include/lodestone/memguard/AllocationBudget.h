#pragma once

#include <cstddef>
#include <cstdint>

namespace lodestone::memguard {

/** A bound on what the code run while it is alive may allocate on this thread: every
 * allocation through `operator new` (std::vector, std::string, ...) and through MRPT's aligned
 * allocator (mrpt::aligned_malloc / aligned_calloc: CMatrixDynamic, point clouds) is charged
 * against `bytes`, summed; the first block of at least kSmallestRefused bytes that would go
 * past it throws std::bad_alloc (a `nothrow` new returns null) before anything is allocated,
 * and the budget then stands aside so the error can be reported. Smaller blocks are refused
 * only past kSmallBlockSlack beyond the limit: a damaged size field asks for a large block (or
 * for very many small ones: a std::deque resized to it), while a few small ones are what code
 * that may not throw allocates near the limit (an exception's text and call stack while MRPT
 * builds it: refusing there ends in std::terminate - found by tests/fuzz/fuzz_observation).
 *
 * Why: MRPT's deserializers trust the size fields they read and allocate - and zero-fill -
 * first, so one damaged size in a rawlog entry takes gigabytes (or, through the aligned
 * allocator's null return, crashes) before the stream can say it is short. A reader sets a
 * budget from what the file could still hold (RawlogReader: a multiple of the bytes left) and
 * turns the refusal into a read error naming the entry.
 *
 * The charging is done by the allocation hooks (libs/memguard/hooks), which every Lodestone
 * executable links (lodestone_add_app / lodestone_add_test); a program without them runs
 * unbounded, as before - hooksInstalled() says which. Budgets nest: the inner one applies
 * until it ends. One per thread at a time is the intended use. */
class AllocationBudget {
  public:
    /** Blocks smaller than this are refused only past the limit plus kSmallBlockSlack. */
    static constexpr std::uint64_t kSmallestRefused = 256 * 1024;
    static constexpr std::uint64_t kSmallBlockSlack = 16 * 1024 * 1024;

    explicit AllocationBudget(std::uint64_t bytes);
    ~AllocationBudget();
    AllocationBudget(const AllocationBudget&) = delete;
    AllocationBudget& operator=(const AllocationBudget&) = delete;

    std::uint64_t limit() const { return limit_; }
    std::uint64_t charged() const { return charged_; }
    /** An allocation was refused: its size (0 if none was). */
    std::uint64_t refused() const { return refused_; }
    bool exceeded() const { return refused_ > 0; }

    /** Whether this process's allocations are charged at all (the hooks are linked in). */
    static bool hooksInstalled();

  private:
    friend bool charge(std::size_t bytes) noexcept;
    std::uint64_t limit_, charged_{0}, refused_{0};
    AllocationBudget* outer_;
};

/** For the hooks: charges `bytes` to this thread's budget, if one is active; false means
 * refuse the allocation. */
bool charge(std::size_t bytes) noexcept;
/** For the hooks: called once from their static initializer. */
void markHooksInstalled() noexcept;

}  // namespace lodestone::memguard
