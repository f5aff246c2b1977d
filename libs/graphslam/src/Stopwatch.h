#pragma once
// Wall-clock timing for the engine's and deciders' statistics (internal to graphslam).
#include <chrono>

namespace lodestone::graphslam {

using Clock = std::chrono::steady_clock;

/** Milliseconds since `t0`. */
inline double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace lodestone::graphslam
