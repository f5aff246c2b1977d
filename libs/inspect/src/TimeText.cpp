#include <lodestone/inspect/TimeText.h>
#include <mrpt/system/datetime.h>

#include <cstdio>

namespace lodestone::inspect {

std::string secondsText(mrpt::Clock::time_point t) {
    if (t == INVALID_TIMESTAMP) return "-";
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.6f", mrpt::Clock::toDouble(t));
    return buf;
}

std::string timeText(mrpt::Clock::time_point t) {
    if (t == INVALID_TIMESTAMP) return "-";
    return secondsText(t) + " (" + mrpt::system::dateTimeToString(t) + " UTC)";
}

}  // namespace lodestone::inspect
