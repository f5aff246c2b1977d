#pragma once

#include <mrpt/core/Clock.h>

#include <string>

namespace lodestone::inspect {

/** "1700000000.250000 (2023/11/14,22:13:20.250000 UTC)": seconds since the epoch and the date. */
std::string timeText(mrpt::Clock::time_point t);

/** Seconds since the epoch with microseconds, or "-" for an invalid timestamp. */
std::string secondsText(mrpt::Clock::time_point t);

}  // namespace lodestone::inspect
