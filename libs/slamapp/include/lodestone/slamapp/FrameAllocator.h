#pragma once

namespace lodestone::slamapp {

/** Keeps the heap's freed frame buffers for the next frame instead of handing them back to the
 * kernel. glibc serves blocks over its mmap threshold (128 KiB at first, raised as blocks are
 * freed) with fresh mappings and trims the heap's free top: every frame's images, depth and
 * decoded PNG rows then come back as new zero-filled pages, and page faults were 12 % of a
 * rawlog run's CPU time (perf, office at 640x480). Raising both thresholds above any frame's
 * size makes the allocator reuse them; the peak stays what the frame loop holds at once. Call
 * once at the start of a process, before threads start. */
void keepFrameBuffersMapped();

}  // namespace lodestone::slamapp
