#include <lodestone/inspect/EntryText.h>
#include <lodestone/inspect/TimeText.h>
#include <lodestone/obs/CObservationMagnetometer.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationIMU.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <cstdio>
#include <sstream>

namespace lodestone::inspect {

namespace {
std::string format(const char* fmt, double a, double b, double c, double d = 0) {
    char buf[160];
    std::snprintf(buf, sizeof(buf), fmt, a, b, c, d);
    return buf;
}

// Loads delay-loaded images so they can be described; a missing file is reported, not fatal.
void loadForDescription(const mrpt::obs::CObservation& obs, std::ostream& out) {
    try {
        obs.load();
    } catch (const std::exception& e) {
        const std::string what = e.what();
        out << "(an external image could not be loaded: " << what.substr(0, what.find('\n'))
            << ")\n";
    }
}

std::string rangeScanContent(const mrpt::obs::CObservation3DRangeScan& s) {
    std::ostringstream o;
    if (s.hasRangeImage) {
        const auto rows = s.rangeImage.rows(), cols = s.rangeImage.cols();
        std::size_t valid = 0;
        for (int r = 0; r < rows; ++r) {
            for (int c = 0; c < cols; ++c) valid += s.rangeImage(r, c) != 0;
        }
        const auto total = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
        o << cols << "x" << rows << " depth " << (total ? 100 * valid / total : 0) << "% valid";
    } else {
        o << "no depth";
    }
    o << (s.hasIntensityImage ? ", RGB" : ", no RGB");
    if (s.hasPoints3D) o << ", " << s.points3D_x.size() << " points";
    return o.str();
}
}  // namespace

std::string shortContent(const mrpt::obs::CObservation& obs) {
    using namespace mrpt::obs;
    if (const auto* m = dynamic_cast<const lodestone::obs::CObservationMagnetometer*>(&obs)) {
        return format("B=(%.2f, %.2f, %.2f) uT |B|=%.2f", m->field.x, m->field.y, m->field.z,
                      m->magnitude());
    }
    if (const auto* imu = dynamic_cast<const CObservationIMU*>(&obs)) {
        std::string s;
        if (imu->has(IMU_X_ACC) && imu->has(IMU_Y_ACC) && imu->has(IMU_Z_ACC)) {
            s += format("acc=(%.2f, %.2f, %.2f) m/s2 ", imu->get(IMU_X_ACC), imu->get(IMU_Y_ACC),
                        imu->get(IMU_Z_ACC));
        }
        if (imu->has(IMU_MAG_X) && imu->has(IMU_MAG_Y) && imu->has(IMU_MAG_Z)) {
            s += format("mag=(%.4f, %.4f, %.4f) ", imu->get(IMU_MAG_X), imu->get(IMU_MAG_Y),
                        imu->get(IMU_MAG_Z));
        }
        return s.empty() ? s : s.substr(0, s.size() - 1);
    }
    if (const auto* odo = dynamic_cast<const CObservationOdometry*>(&obs)) {
        std::string s = format("pose=(%.3f m, %.3f m, %.2f deg)", odo->odometry.x(),
                               odo->odometry.y(), mrpt::RAD2DEG(odo->odometry.phi()));
        if (odo->hasEncodersInfo) {
            s += " ticks L=" + std::to_string(odo->encoderLeftTicks) +
                 " R=" + std::to_string(odo->encoderRightTicks);
        }
        return s;
    }
    if (const auto* scan = dynamic_cast<const CObservation3DRangeScan*>(&obs)) {
        return rangeScanContent(*scan);
    }
    return {};
}

std::string observationLine(const mrpt::obs::CObservation& obs) {
    std::ostringstream o;
    o << secondsText(obs.timestamp) << "  " << obs.GetRuntimeClass()->className << "  "
      << (obs.sensorLabel.empty() ? "(no label)" : obs.sensorLabel);
    const std::string content = shortContent(obs);
    if (!content.empty()) o << "  " << content;
    return o.str();
}

namespace {
// MRPT's own description of an object; it throws on values MRPT read but cannot name (an
// enum holding a number its type lacks): said in the text rather than ending the listing.
template <typename T>
void mrptDescription(const T& object, std::ostream& out) {
    try {
        object.getDescriptionAsText(out);
    } catch (const std::exception& e) {
        out << "\n(MRPT cannot describe this object: " << e.what() << ")\n";
    }
}
}  // namespace

void describeEntry(const mrpt::serialization::CSerializable& entry, std::ostream& out) {
    out << "Class: " << entry.GetRuntimeClass()->className << "\n";
    if (const auto* obs = dynamic_cast<const mrpt::obs::CObservation*>(&entry)) {
        loadForDescription(*obs, out);
        mrptDescription(*obs, out);
    } else if (const auto* sf = dynamic_cast<const mrpt::obs::CSensoryFrame*>(&entry)) {
        out << "Sensory frame with " << sf->size() << " observation(s)\n";
        std::size_t i = 0;
        for (const auto& o : *sf) {
            if (!o) continue;
            out << "\n--- observation " << i++ << ": " << o->GetRuntimeClass()->className
                << " ---\n";
            loadForDescription(*o, out);
            mrptDescription(*o, out);
        }
    } else if (const auto* acts = dynamic_cast<const mrpt::obs::CActionCollection*>(&entry)) {
        out << "Action collection with " << acts->size() << " action(s)\n";
        std::size_t i = 0;
        for (const auto& a : *acts) {
            out << "\n--- action " << i++ << ": " << a->GetRuntimeClass()->className << " ---\n";
            mrptDescription(*a, out);
        }
    }
}

}  // namespace lodestone::inspect
