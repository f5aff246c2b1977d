#include <lodestone/obs/CObservationWheelDrop.h>
#include <mrpt/serialization/CArchive.h>

#include "SerializedBool.h"

namespace lodestone::obs {

IMPLEMENTS_SERIALIZABLE(CObservationWheelDrop, mrpt::obs::CObservation, lodestone::obs)

// Version history:
//   0: timestamp, sensorLabel, leftDropped, rightDropped.
uint8_t CObservationWheelDrop::serializeGetVersion() const { return 0; }

void CObservationWheelDrop::serializeTo(mrpt::serialization::CArchive& out) const {
    out << timestamp << sensorLabel << leftDropped << rightDropped;
}

void CObservationWheelDrop::serializeFrom(mrpt::serialization::CArchive& in, uint8_t version) {
    switch (version) {
        case 0:
            in >> timestamp >> sensorLabel;
            leftDropped = detail::readBool(in, "CObservationWheelDrop", "left_dropped");
            rightDropped = detail::readBool(in, "CObservationWheelDrop", "right_dropped");
            break;
        default:
            MRPT_THROW_UNKNOWN_SERIALIZATION_VERSION(version);
    }
}

void CObservationWheelDrop::getDescriptionAsText(std::ostream& o) const {
    CObservation::getDescriptionAsText(o);
    o << "Left wheel dropped: " << (leftDropped ? "yes" : "no") << "\n";
    o << "Right wheel dropped: " << (rightDropped ? "yes" : "no") << "\n";
}

std::string CObservationWheelDrop::exportTxtHeader() const {
    return "  LEFT_DROPPED  RIGHT_DROPPED";
}

std::string CObservationWheelDrop::exportTxtDataRow() const {
    return std::string(" ") + (leftDropped ? "1" : "0") + " " + (rightDropped ? "1" : "0");
}

}  // namespace lodestone::obs
