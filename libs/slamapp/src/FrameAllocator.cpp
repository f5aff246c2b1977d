#include <lodestone/slamapp/FrameAllocator.h>

#include <malloc.h>

namespace lodestone::slamapp {

void keepFrameBuffersMapped() {
    // 64 MiB: above a 1280x960 colour frame (3.7 MB) many times over; a larger block (a whole
    // map's cloud at the end) is still mapped and returned on its own.
    constexpr int kMmapThreshold = 64 << 20;
    // Free memory at the heap's top kept for reuse before trimming.
    constexpr int kTrimThreshold = 256 << 20;
    mallopt(M_MMAP_THRESHOLD, kMmapThreshold);
    mallopt(M_TRIM_THRESHOLD, kTrimThreshold);
}

}  // namespace lodestone::slamapp
