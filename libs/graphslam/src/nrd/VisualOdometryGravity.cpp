// VisualOdometryNRD: each node's up, from the IMU's accelerometer (odometry::GravityEstimator),
// with the carrier's velocity change over the averaging window - what an accelerometer cannot
// tell from a tilt - measured by VO and taken out.
#include <lodestone/graphslam/nrd/VisualOdometryNRD.h>

#include <cmath>

namespace lodestone::graphslam {

const std::pair<double, mrpt::poses::CPose3D>* VisualOdometryNRD::trackedNear(double t) const {
    const std::pair<double, mrpt::poses::CPose3D>* best = nullptr;
    for (const auto& c : chained_) {
        if (!best || std::abs(c.first - t) < std::abs(best->first - t)) best = &c;
    }
    // (a frame further off than this: VO did not track there)
    return best && std::abs(best->first - t) <= 0.1 ? best : nullptr;
}

std::optional<AttitudePrior> VisualOdometryNRD::measuredUp(double t) const {
    const double W = params_.gravity.windowSeconds, d = params_.gravityVelocitySeconds;
    // VO's mean velocity over the last d seconds before each end of the window, in its chain's
    // frame; their difference over W is the window's mean acceleration.
    const auto e1 = trackedNear(t), s1 = trackedNear(t - d), e0 = trackedNear(t - W),
               s0 = trackedNear(t - W - d);
    if (!e1 || !s1 || !e0 || !s0 || !(e1->first > s1->first) || !(e0->first > s0->first))
        return std::nullopt;
    const auto velocity = [](const auto* a, const auto* b) {
        const Eigen::Vector3d pa(a->second.x(), a->second.y(), a->second.z()),
            pb(b->second.x(), b->second.y(), b->second.z());
        return Eigen::Vector3d((pb - pa) / (b->first - a->first));
    };
    const Eigen::Vector3d dv = velocity(e1, s1) - velocity(e0, s0);  // (chain's frame)
    // Those velocities are the middles' (d / 2 before each end): the accelerometer's window is
    // taken between the same instants, its up then turned to t by the gyro.
    const double tm = t - 0.5 * d;
    const auto m = trackedNear(tm);
    const auto turn = gyro_.between(tm, t);
    if (!m || !turn) return std::nullopt;
    // Into the sensor's frame at tm: the robot's there (the chain's frame nearest), then the
    // sensor's on the robot.
    const Eigen::Matrix3d S = gravity_.sensorOnRobot().linear();
    const Eigen::Matrix3d R = m->second.getRotationMatrix().asEigen();
    const Eigen::Vector3d acceleration = S.transpose() * (R.transpose() * dv) / W;
    const double sigma = std::sqrt(2.0) * params_.gravityVelocitySigma / W;
    const auto g = gravity_.at(tm, acceleration, sigma);
    if (!g) return std::nullopt;
    // (the gyro's body rotation from tm to t: the sensor's frame; then the robot's)
    return AttitudePrior{S * (turn->R.transpose() * g->up), std::hypot(g->sigma, turn->sigma)};
}

}  // namespace lodestone::graphslam
