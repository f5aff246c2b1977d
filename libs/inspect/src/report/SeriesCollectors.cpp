#include <lodestone/inspect/report/SeriesCollectors.h>
#include <lodestone/obs/CObservationMagnetometer.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <cmath>

namespace lodestone::inspect::report {

namespace {
constexpr double kKeepDistance = 0.01;             // [m]
constexpr double kKeepTurn = 2.0 * M_PI / 180.0;   // [rad]
const char* kActionsLabel = "actions (CActionRobotMovement2D)";
}  // namespace

void SeriesCollectors::addPose(OdometryPath& path, const mrpt::poses::CPose2D& pose) {
    ++path.count;
    if (!std::isfinite(pose.x()) || !std::isfinite(pose.y()) || !std::isfinite(pose.phi())) return;
    if (!path.points.empty()) {
        const auto& last = path.points.back();
        const double d = std::hypot(pose.x() - last.x(), pose.y() - last.y());
        const double turn = std::abs(std::remainder(pose.phi() - last.phi(), 2 * M_PI));
        if (d < kKeepDistance && turn < kKeepTurn) return;
        path.length += d;
    }
    path.points.push_back(pose);
    if (path.points.size() > kMaxPathPoints) {
        std::size_t kept = 0;
        for (std::size_t i = 0; i < path.points.size(); i += 2) path.points[kept++] = path.points[i];
        path.points.resize(kept);
    }
}

void SeriesCollectors::addObservation(const mrpt::obs::CObservation& obs, double time) {
    if (const auto* m = dynamic_cast<const obs::CObservationMagnetometer*>(&obs)) {
        auto& s = magnetometers_[m->sensorLabel];
        s.label = m->sensorLabel;
        ++s.count;
        if (!std::isfinite(time)) return;
        s.channels[0].at(time).add(m->field.x);
        s.channels[1].at(time).add(m->field.y);
        s.channels[2].at(time).add(m->field.z);
        s.channels[3].at(time).add(m->magnitude());
    } else if (const auto* o = dynamic_cast<const mrpt::obs::CObservationOdometry*>(&obs)) {
        auto& p = odometry_[o->sensorLabel];
        p.label = o->sensorLabel;
        addPose(p, o->odometry);
    }
}

void SeriesCollectors::addActions(const mrpt::serialization::CSerializable& entry) {
    const auto* actions = dynamic_cast<const mrpt::obs::CActionCollection*>(&entry);
    if (!actions) return;
    for (const auto& a : *actions) {
        const auto* move = dynamic_cast<const mrpt::obs::CActionRobotMovement2D*>(a.get());
        if (!move || !move->poseChange) continue;
        actions_pose_ = actions_pose_ + move->poseChange->getMeanVal();
        auto& p = odometry_[kActionsLabel];
        p.label = kActionsLabel;
        addPose(p, actions_pose_);
    }
}

std::vector<MagnetometerSeries> SeriesCollectors::magnetometers() const {
    std::vector<MagnetometerSeries> out;
    for (const auto& [label, s] : magnetometers_) out.push_back(s);
    return out;
}

std::vector<OdometryPath> SeriesCollectors::odometry() const {
    std::vector<OdometryPath> out;
    for (const auto& [label, p] : odometry_) out.push_back(p);
    return out;
}

}  // namespace lodestone::inspect::report
