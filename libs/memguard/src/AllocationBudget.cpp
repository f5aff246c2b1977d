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
    const bool over = bytes > b->limit_ || b->charged_ > b->limit_ - bytes;
    if (over && bytes >= AllocationBudget::kSmallestRefused) {
        b->refused_ = bytes;
        return false;
    }
    b->charged_ += bytes;
    return true;
}

void markHooksInstalled() noexcept { installed.store(true); }

}  // namespace lodestone::memguard
