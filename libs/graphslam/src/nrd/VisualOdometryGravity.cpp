// VisualOdometryNRD: each node's up, from the IMU's accelerometer (odometry::GravityEstimator),
// with the carrier's velocity change over the averaging window - what an accelerometer cannot
// tell from a tilt - measured by VO and taken out; and from the level surfaces the node's depth
// holds (LevelFloor), with its height above the floor.
#include <lodestone/graphslam/nrd/VisualOdometryNRD.h>
#include <lodestone/odometry/RgbdObservationFrame.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace lodestone::graphslam {

std::optional<std::size_t> VisualOdometryNRD::trackedNear(double t) const {
    std::optional<std::size_t> best;
    for (std::size_t i = 0; i < chained_.size(); ++i) {
        if (!best || std::abs(chained_[i].first - t) < std::abs(chained_[*best].first - t))
            best = i;
    }
    // (a frame further off than this: VO did not track there)
    if (best && std::abs(chained_[*best].first - t) <= 0.1) return best;
    return std::nullopt;
}

std::optional<AttitudePrior> VisualOdometryNRD::measuredUp(double t) const {
    const double W = params_.gravity.windowSeconds, d = params_.gravityVelocitySeconds;
    // VO's mean velocity over the last d seconds before each end of the window, in its chain's
    // frame; their difference over W is the window's mean acceleration.
    const auto e1 = trackedNear(t), s1 = trackedNear(t - d), e0 = trackedNear(t - W),
               s0 = trackedNear(t - W - d);
    if (!e1 || !s1 || !e0 || !s0 || !(chained_[*e1].first > chained_[*s1].first) ||
        !(chained_[*e0].first > chained_[*s0].first))
        return std::nullopt;
    const auto position = [&](std::size_t i) {
        const auto& p = chained_[i].second;
        return Eigen::Vector3d(p.x(), p.y(), p.z());
    };
    const auto seconds = [&](std::size_t a, std::size_t b) {
        return chained_[b].first - chained_[a].first;
    };
    const Eigen::Vector3d dv =
        (position(*e1) - position(*s1)) / seconds(*s1, *e1) -
        (position(*e0) - position(*s0)) / seconds(*s0, *e0);  // (chain's frame)
    // How well VO knew those velocities: its own uncertainty of each end (against its
    // reference, at most their sum), never better than gravityVelocitySigma. Where VO's steps
    // left a direction to the depth's loose axes (a plain wall ahead: the height), the
    // velocity there is unknown and the window says nothing of the carrier's acceleration -
    // an up taken from it at 0.03 m/s would tilt the node by degrees, and surely.
    const Eigen::Matrix3d velocityCovariance =
        (chained_covariance_[*e1] + chained_covariance_[*s1]) / std::pow(seconds(*s1, *e1), 2) +
        (chained_covariance_[*e0] + chained_covariance_[*s0]) / std::pow(seconds(*s0, *e0), 2);
    const double vo =
        std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(velocityCovariance)
                                    .eigenvalues()
                                    .maxCoeff()));
    // Those velocities are the middles' (d / 2 before each end): the accelerometer's window is
    // taken between the same instants, its up then turned to t by the gyro.
    const double tm = t - 0.5 * d;
    const auto m = trackedNear(tm);
    const auto turn = gyro_.between(tm, t);
    if (!m || !turn) return std::nullopt;
    // Into the sensor's frame at tm: the robot's there (the chain's frame nearest), then the
    // sensor's on the robot.
    const Eigen::Matrix3d S = gravity_.sensorOnRobot().linear();
    const Eigen::Matrix3d R = chained_[*m].second.getRotationMatrix().asEigen();
    const Eigen::Vector3d acceleration = S.transpose() * (R.transpose() * dv) / W;
    const double sigma = std::hypot(std::sqrt(2.0) * params_.gravityVelocitySigma, vo) / W;
    const auto g = gravity_.at(tm, acceleration, sigma);
    if (!g) return std::nullopt;
    // (the gyro's body rotation from tm to t: the sensor's frame; then the robot's)
    return AttitudePrior{S * (turn->R.transpose() * g->up), std::hypot(g->sigma, turn->sigma)};
}

std::optional<AttitudePrior> VisualOdometryNRD::nodeAttitude(
    TNodeID id, double t, const mrpt::obs::CObservation3DRangeScan& scan) {
    std::optional<AttitudePrior> up;
    if (params_.useGravity) {
        up = measuredUp(t);
        if (up) ++attitude_priors_;
    }
    if (params_.floorLevel && frame_) {
        const vision::DepthCloud cloud =
            frame_cloud_ ? *frame_cloud_
                         : vision::sampleDepthCloud(*frame_, params_.visual.depthSampling);
        const auto poseOf = [this](TNodeID n) {
            Eigen::Isometry3d T;
            T.matrix() = m_graph->nodes.at(n)
                             .getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>()
                             .asEigen();
            return T;
        };
        const auto floor =
            floor_.observe(id, cloud, odometry::opticalFrameOnRobot(scan.sensorPose), poseOf);
        if (floor && up) {
            // (a floor the accelerometer says is not level - a ramp - is left out)
            const auto both = fuseUps(*up, *floor);
            if (both)
                up = both;
            else
                ++floor_disagreed_;
        } else if (floor) {
            up = floor;
        }
    }
    if (!up && params_.carrierTiltSigma > 0) {
        up = AttitudePrior{Eigen::Vector3d::UnitZ(), params_.carrierTiltSigma};
        ++carrier_ups_;
    }
    if (params_.carrierHeightSigma > 0) {
        if (!up) up = AttitudePrior{};  // (a height, no up)
        up->heightSigma = params_.carrierHeightSigma;
    }
    return up;
}

}  // namespace lodestone::graphslam
