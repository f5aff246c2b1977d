// MagneticWindowERD's magnetometers: the one queried and, walked back, its mirror image.
#include <lodestone/graphslam/erd/magnetic/MagneticWindowERD.h>

#include <cmath>

namespace lodestone::graphslam {

namespace {
/** [m] two mountings closer than this read the same line of the floor's field (well under the
 * field's correlation length). */
constexpr double kSameLine = 0.05;
/** [m] a sensor this close to the centre line is its own mirror. */
constexpr double kCentred = 0.02;
}  // namespace

bool MagneticWindowERD::takeReading(const MagneticSample& m) {
    if (params_.sensorLabel.empty()) params_.sensorLabel = m.sensorLabel;
    const auto known = sensors_.find(m.sensorLabel);
    if (known != sensors_.end()) return true;
    const Eigen::Vector3d at(m.sensorPose.x(), m.sensorPose.y(), m.sensorPose.z());
    const auto track = [&] {
        return std::make_unique<magnetic::SupernodeTrack>(
            magnetic::SupernodeTrack::Params{params_.step, params_.window, params_.step}, 3);
    };
    if (m.sensorLabel == params_.sensorLabel) {
        sensors_[m.sensorLabel] = {track(), at};
        return true;
    }
    // Another magnetometer: kept if it is the queried one's mirror image across the centre line.
    const auto queriedOne = sensors_.find(params_.sensorLabel);
    if (!params_.mirrorSensors || !mirror_.empty() || queriedOne == sensors_.end()) return false;
    const Eigen::Vector3d& p = queriedOne->second.position;
    const Eigen::Vector3d image(p.x(), -p.y(), p.z());
    if (std::abs(p.y()) <= kCentred || (at - image).norm() > kSameLine) return false;
    mirror_ = m.sensorLabel;
    sensors_[m.sensorLabel] = {track(), at};
    return true;
}

const magnetic::SupernodeTrack& MagneticWindowERD::queried() const {
    return *sensors_.at(params_.sensorLabel).track;
}

const magnetic::SupernodeTrack& MagneticWindowERD::mirrored() const {
    return mirror_.empty() ? queried() : *sensors_.at(mirror_).track;
}

}  // namespace lodestone::graphslam
