#include "BudgetedMatAllocator.h"

#include <lodestone/memguard/AllocationBudget.h>

#include <opencv2/core/mat.hpp>

#include <limits>
#include <mutex>
#include <new>

namespace lodestone::io::detail {

namespace {

/** OpenCV's standard allocator, with each new block charged first (a refusal throws
 * std::bad_alloc out of cv::Mat::create, which rethrows what its default allocator throws). */
class BudgetedMatAllocator : public cv::MatAllocator {
  public:
    explicit BudgetedMatAllocator(cv::MatAllocator* standard) : standard_(standard) {}

    cv::UMatData* allocate(int dims, const int* sizes, int type, void* data, size_t* step,
                           cv::AccessFlag flags, cv::UMatUsageFlags usage) const override {
        if (!data && !memguard::charge(bytesOf(dims, sizes, type))) throw std::bad_alloc();
        return standard_->allocate(dims, sizes, type, data, step, flags, usage);
    }
    bool allocate(cv::UMatData* data, cv::AccessFlag flags, cv::UMatUsageFlags usage) const override {
        return standard_->allocate(data, flags, usage);
    }
    void deallocate(cv::UMatData* data) const override { standard_->deallocate(data); }

  private:
    /** The block's size; saturates at the largest size_t (always refused) on overflow. */
    static std::size_t bytesOf(int dims, const int* sizes, int type) {
        constexpr std::size_t kMax = std::numeric_limits<std::size_t>::max();
        std::size_t total = CV_ELEM_SIZE(type);
        for (int i = 0; i < dims; ++i) {
            const auto n = static_cast<std::size_t>(sizes[i] < 0 ? 0 : sizes[i]);
            if (n != 0 && total > kMax / n) return kMax;
            total *= n;
        }
        return total;
    }
    cv::MatAllocator* standard_;
};

}  // namespace

void installBudgetedMatAllocator() {
    static std::once_flag once;
    std::call_once(once, [] {
        static BudgetedMatAllocator allocator(cv::Mat::getStdAllocator());
        cv::Mat::setDefaultAllocator(&allocator);
    });
}

}  // namespace lodestone::io::detail
