#include <lodestone/memguard/AllocationBudget.h>

#include <atomic>

namespace lodestone::memguard {

namespace {
thread_local AllocationBudget* active = nullptr;
std::atomic<bool> installed{false};
}  // namespace

AllocationBudget::AllocationBudget(std::uint64_t bytes) : limit_(bytes), outer_(active) {
    active = this;
}

AllocationBudget::~AllocationBudget() { active = outer_; }

bool AllocationBudget::hooksInstalled() { return installed.load(); }

bool charge(std::size_t bytes) noexcept {
    AllocationBudget* b = active;
    if (!b || b->refused_ > 0) return true;  // none active, or already refused: stand aside
    // Past the limit, a large block is refused; small ones only past the slack beyond it.
    const std::uint64_t limit = bytes >= AllocationBudget::kSmallestRefused
                                    ? b->limit_
                                    : b->limit_ + AllocationBudget::kSmallBlockSlack;
    if (bytes > limit || b->charged_ > limit - bytes) {
        b->refused_ = bytes;
        return false;
    }
    b->charged_ += bytes;
    return true;
}

void markHooksInstalled() noexcept { installed.store(true); }

}  // namespace lodestone::memguard
