#include <lodestone/sim/HandheldMotion.h>

#include <cmath>

namespace lodestone::sim {

HandheldMotion::HandheldMotion(const MotionPlan& plan, const HandheldSpec& spec, Random rng)
    : plan_(plan), spec_(spec) {
    const double deg = M_PI / 180;
    const double amplitude[6] = {spec.sway, spec.bob, 0.0, spec.shakeDeg * deg, spec.shakeDeg * deg,
                                 spec.shakeDeg * deg};
    for (int a = 0; a < 6; ++a) {
        for (auto& w : waves_[static_cast<std::size_t>(a)]) {
            // Three waves share the amplitude (their sum peaks near it, rarely beyond).
            w = {amplitude[a] / 2, rng.uniform(0.3, 2.0), rng.uniform(0, 2 * M_PI)};
        }
    }
}

double HandheldMotion::offset(int axis, double t) const {
    double v = 0;
    for (const auto& w : waves_[static_cast<std::size_t>(axis)])
        v += w.amplitude * std::sin(2 * M_PI * w.frequency * t + w.phase);
    return v;
}

Eigen::Isometry3d HandheldMotion::poseAt(double t) const {
    const RobotPose p = plan_.poseAt(t);
    const double yaw = p.yaw + offset(3, t);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    // Sway is sideways of the carrier's heading; the camera rides on any lift of the carrier.
    const Eigen::Vector2d left(-std::sin(p.yaw), std::cos(p.yaw));
    const Eigen::Vector2d xy = Eigen::Vector2d(p.x, p.y) + offset(0, t) * left;
    T.translation() = Eigen::Vector3d(xy.x(), xy.y(), p.z + spec_.height + offset(1, t));
    T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(offset(4, t), Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(offset(5, t), Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    return T;
}

}  // namespace lodestone::sim
