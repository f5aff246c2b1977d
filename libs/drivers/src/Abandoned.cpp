#include "Abandoned.h"

#include <mutex>
#include <vector>

namespace lodestone::drivers::detail {

void abandon(const void* driver) {
    static std::mutex mutex;
    static auto* kept = new std::vector<const void*>;  // never freed: that is the point
    std::lock_guard<std::mutex> lock(mutex);
    kept->push_back(driver);
}

}  // namespace lodestone::drivers::detail
