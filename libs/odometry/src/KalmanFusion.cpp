#include <lodestone/odometry/KalmanFusion.h>

#include <Eigen/Dense>
#include <cmath>

namespace lodestone::odometry {

KalmanFusion::KalmanFusion(double weightC, double processNoise, double measurementNoise)
    : c_(weightC), q_(processNoise), r_(measurementNoise) {}

void KalmanFusion::reset(const mrpt::poses::CPosePDFGaussian& start) {
    pose_ = start;
    wheel_ = visual_ = start.mean;
    last_wheel_ = last_visual_ = {start.mean.x(), start.mean.y(), start.mean.phi()};
    state_.setZero();
    state_.row(0) = last_wheel_.transpose();
    cov_.setZero();
    for (int a = 0; a < 3; ++a) cov_.block<2, 2>(0, 2 * a) = Eigen::Matrix2d::Identity() * 1e-6;
    started_ = true;
}

const mrpt::poses::CPosePDFGaussian& KalmanFusion::step(const OdometryStep& s) {
    if (!started_) reset(pose_);
    const double dt = std::max(1e-3, s.dt);
    // The two tracks, with headings kept continuous (no wrap at +-pi) for the filter.
    const auto advance = [](mrpt::poses::CPose2D& track, Eigen::Vector3d& unwrapped,
                            const mrpt::poses::CPose2D& motion) {
        track = track + motion;
        const double heading =
            unwrapped.z() + std::remainder(track.phi() - unwrapped.z(), 2 * M_PI);
        const Eigen::Vector3d before = unwrapped;
        unwrapped = {track.x(), track.y(), heading};
        return before;
    };
    const Eigen::Vector3d wheelBefore = advance(wheel_, last_wheel_, s.wheel.mean);
    // Without a visual estimate, the visual track moves with the wheels.
    const Eigen::Vector3d visualBefore =
        advance(visual_, last_visual_, s.visual ? s.visual->mean : s.wheel.mean);

    // Eq. (2): H maps (wheel_k, visual_k, wheel_k-1, visual_k-1) to position and velocity.
    Eigen::Matrix<double, 2, 4> H;
    H << c_, 1 - c_, 0, 0,  //
        c_ / dt, (1 - c_) / dt, -c_ / dt, -(1 - c_) / dt;
    Eigen::Matrix2d F;
    F << 1, dt, 0, 1;
    Eigen::Matrix2d Q;
    Q << dt * dt * dt / 3, dt * dt / 2, dt * dt / 2, dt;
    Q *= q_;
    const Eigen::Matrix2d R = Eigen::Vector2d(r_, 2 * r_ / (dt * dt)).asDiagonal();
    Eigen::Vector3d fused;
    for (int a = 0; a < 3; ++a) {
        const Eigen::Vector4d sources(last_wheel_[a], last_visual_[a], wheelBefore[a],
                                      visualBefore[a]);
        const Eigen::Vector2d z = H * sources;
        Eigen::Vector2d x = F * state_.col(a);
        Eigen::Matrix2d P = F * cov_.block<2, 2>(0, 2 * a) * F.transpose() + Q;
        const Eigen::Matrix2d K = P * (P + R).inverse();
        x += K * (z - x);
        P = (Eigen::Matrix2d::Identity() - K) * P;
        state_.col(a) = x;
        cov_.block<2, 2>(0, 2 * a) = P;
        fused[a] = x[0];
    }
    const mrpt::poses::CPose2D before = pose_.mean;
    pose_.mean = mrpt::poses::CPose2D(fused.x(), fused.y(), fused.z());
    // The filter keeps no increment covariance of its own; the wheels' is the honest stand-in
    // (the blend leans on them, weight C).
    increment_.mean = pose_.mean - before;
    increment_.cov = s.wheel.cov;
    // Eq. (2) blends the tracks' positions with weight C on the wheels' (the visual track
    // follows the wheels where VO has nothing).
    wheel_gain_ = (s.visual ? c_ : 1.0) * Eigen::Matrix3d::Identity();
    pose_.cov.setZero();
    for (int a = 0; a < 3; ++a) pose_.cov(a, a) = cov_(0, 2 * a);
    return pose_;
}

}  // namespace lodestone::odometry
