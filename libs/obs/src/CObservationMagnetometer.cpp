#include <lodestone/obs/CObservationMagnetometer.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/system/datetime.h>

#include "SerializedBool.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace lodestone::obs {

IMPLEMENTS_SERIALIZABLE(CObservationMagnetometer, mrpt::obs::CObservation, lodestone::obs)

// Version history:
//   0: timestamp, sensorLabel, sensorPose, field, noiseStd, temperature (flag + value),
//      calibrated.
uint8_t CObservationMagnetometer::serializeGetVersion() const { return 0; }

void CObservationMagnetometer::serializeTo(mrpt::serialization::CArchive& out) const {
    out << timestamp << sensorLabel << sensorPose;
    out << field.x << field.y << field.z;
    out << noiseStd.x << noiseStd.y << noiseStd.z;
    out << temperature.has_value() << temperature.value_or(0.0);
    out << calibrated;
}

void CObservationMagnetometer::serializeFrom(mrpt::serialization::CArchive& in, uint8_t version) {
    switch (version) {
        case 0: {
            in >> timestamp >> sensorLabel >> sensorPose;
            in >> field.x >> field.y >> field.z;
            in >> noiseStd.x >> noiseStd.y >> noiseStd.z;
            const bool hasTemperature =
                detail::readBool(in, "CObservationMagnetometer", "has_temperature");
            double t = 0;
            in >> t;
            temperature = hasTemperature ? std::optional<double>(t) : std::nullopt;
            calibrated = detail::readBool(in, "CObservationMagnetometer", "calibrated");
        } break;
        default:
            MRPT_THROW_UNKNOWN_SERIALIZATION_VERSION(version);
    }
}

double CObservationMagnetometer::magnitude() const { return field.norm(); }

void CObservationMagnetometer::getDescriptionAsText(std::ostream& o) const {
    CObservation::getDescriptionAsText(o);
    o << std::fixed << std::setprecision(3);
    o << "Sensor pose on the robot: " << sensorPose << "\n";
    o << "Field (sensor frame) [uT]: (" << field.x << ", " << field.y << ", " << field.z
      << ")  |B| = " << magnitude() << "\n";
    o << "Noise std [uT]: (" << noiseStd.x << ", " << noiseStd.y << ", " << noiseStd.z << ")\n";
    o << "Temperature [degC]: ";
    if (temperature) {
        o << *temperature << "\n";
    } else {
        o << "(not reported)\n";
    }
    o << "Calibrated: " << (calibrated ? "yes" : "no") << "\n";
}

std::string CObservationMagnetometer::exportTxtHeader() const {
    return "  MAG_X_uT  MAG_Y_uT  MAG_Z_uT  STD_X_uT  STD_Y_uT  STD_Z_uT  TEMP_degC  CALIBRATED";
}

std::string CObservationMagnetometer::exportTxtDataRow() const {
    std::ostringstream s;
    s << std::setprecision(9);
    s << ' ' << field.x << ' ' << field.y << ' ' << field.z << ' ' << noiseStd.x << ' '
      << noiseStd.y << ' ' << noiseStd.z << ' ' << (temperature ? *temperature : std::nan(""))
      << ' ' << (calibrated ? 1 : 0);
    return s.str();
}

}  // namespace lodestone::obs
