#include <lodestone/obs/CObservationWheelDrop.h>
#include <mrpt/serialization/CArchive.h>

#include <lodestone/obs/SerializedBool.h>

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
            leftDropped = readBool(in, "CObservationWheelDrop", "left_dropped");
            rightDropped = readBool(in, "CObservationWheelDrop", "right_dropped");
            break;
        default:
            MRPT_THROW_UNKNOWN_SERIALIZATION_VERSION(version);
    }
}

void CObservationWheelDrop::getDescriptionAsText(std::ostream& o) const {
    CObservation::getDescriptionAsText(o);
    o << "Lodestone wheel-drop switches of a mobile base (class lodestone::obs::CObservationWheelDrop)\n";
    o << "Emitted when a switch changes; a dropped wheel hangs free, i.e. the robot is being lifted\n";
    o << "Left wheel dropped: " << (leftDropped ? "yes" : "no") << "\n";
    o << "Right wheel dropped: " << (rightDropped ? "yes" : "no") << "\n";
    o << "Robot state: "
      << (lifted() ? "lifted (Lodestone's kidnap detector starts a kidnap here: odometry no longer "
                     "describes the motion)"
                   : "on the floor (both wheels down)")
      << "\n";
}

std::string CObservationWheelDrop::exportTxtHeader() const {
    return "  LEFT_DROPPED  RIGHT_DROPPED";
}

std::string CObservationWheelDrop::exportTxtDataRow() const {
    return std::string(" ") + (leftDropped ? "1" : "0") + " " + (rightDropped ? "1" : "0");
}

}  // namespace lodestone::obs
