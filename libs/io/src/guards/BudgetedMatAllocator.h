#pragma once

namespace lodestone::io::detail {

/** Makes OpenCV's default cv::Mat allocator charge memguard's budget before it allocates.
 * MRPT's CImage stores its pixels in a cv::Mat sized from the width and height it reads, and
 * OpenCV takes the memory with malloc, which the allocation hooks do not see: a damaged image
 * size allocated terabytes (found by tests/fuzz/fuzz_rawlog). With no budget active on the
 * thread this costs one thread-local read. Idempotent; installed with the read guards. */
void installBudgetedMatAllocator();

}  // namespace lodestone::io::detail
