#include "EntryChecks.h"

#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <cstdint>
#include <cstring>
#include <type_traits>
#include <mrpt/obs/CSensoryFrame.h>

namespace lodestone::io::detail {

namespace {
using mrpt::obs::CActionRobotMovement2D;
using mrpt::obs::CObservation3DRangeScan;

// MRPT reads a bool or an enum by copying the stream's bytes into it: a value the type lacks
// is a damaged field, and reading it as that type is undefined behaviour - so it is read as
// the bytes it holds.
bool validBool(const bool& b) {
    std::uint8_t byte = 0;
    std::memcpy(&byte, &b, 1);
    return byte <= 1;
}

template <typename Enum>
long long rawEnum(const Enum& e) {
    std::underlying_type_t<Enum> value{};
    std::memcpy(&value, &e, sizeof value);
    return static_cast<long long>(value);
}

std::string damagedObservation(const mrpt::obs::CObservation& obs) {
    if (const auto* odo = dynamic_cast<const mrpt::obs::CObservationOdometry*>(&obs)) {
        if (!validBool(odo->hasEncodersInfo) || !validBool(odo->hasVelocities)) {
            return "CObservationOdometry flag byte (hasEncodersInfo / hasVelocities) is neither 0 nor 1";
        }
    }
    if (const auto* scan = dynamic_cast<const CObservation3DRangeScan*>(&obs)) {
        const long long channel = rawEnum(scan->intensityImageChannel);
        if (channel != CObservation3DRangeScan::CH_VISIBLE && channel != CObservation3DRangeScan::CH_IR) {
            return "intensity channel id " + std::to_string(channel) + " is neither visible (0) nor IR (1)";
        }
    }
    return {};
}

// CActionRobotMovement2D's flag bytes are not checked: MRPT's own localization_demo.rawlog
// holds 8 in hasEncodersInfo (left unset by an old writer), so RawlogSource reads those bytes
// itself and takes anything but 0 / 1 as "unknown".
std::string damagedAction(const mrpt::obs::CAction& action) {
    if (const auto* move = dynamic_cast<const CActionRobotMovement2D*>(&action)) {
        const long long method = rawEnum(move->estimationMethod);
        if (method != CActionRobotMovement2D::emOdometry && method != CActionRobotMovement2D::emScan2DMatching) {
            return "CActionRobotMovement2D estimation method " + std::to_string(method) + " is unknown";
        }
    }
    return {};
}
}  // namespace

std::string damagedPart(const mrpt::serialization::CSerializable& entry) {
    if (const auto* obs = dynamic_cast<const mrpt::obs::CObservation*>(&entry)) {
        return damagedObservation(*obs);
    }
    std::size_t i = 0;
    if (const auto* sf = dynamic_cast<const mrpt::obs::CSensoryFrame*>(&entry)) {
        for (const auto& o : *sf) {
            if (!o) return "observation " + std::to_string(i) + " of the sensory frame is null";
            if (auto why = damagedObservation(*o); !why.empty()) {
                return "observation " + std::to_string(i) + " of the sensory frame: " + why;
            }
            ++i;
        }
    } else if (const auto* actions = dynamic_cast<const mrpt::obs::CActionCollection*>(&entry)) {
        for (const auto& a : *actions) {
            if (!a) return "action " + std::to_string(i) + " of the action collection is null";
            if (auto why = damagedAction(*a); !why.empty()) return why;
            ++i;
        }
    } else if (const auto* action = dynamic_cast<const mrpt::obs::CAction*>(&entry)) {
        return damagedAction(*action);
    }
    return {};
}

}  // namespace lodestone::io::detail
