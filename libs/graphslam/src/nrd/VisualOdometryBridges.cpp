// VisualOdometryNRD across a VO gap: the bridges from the last tracked frame - the last
// velocity's, the gyro's, and the gyro's corrected by the gap's depth (the frames VO did not
// track still see walls and floors, which measure the translation the motion model guesses:
// odometry::DepthBridge), or without a gyro the depth's turn and translation both.
#include <lodestone/graphslam/Se3Pose.h>
#include <lodestone/graphslam/nrd/VisualOdometryNRD.h>
#include <lodestone/vision/So3.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lodestone::graphslam {

std::string VisualOdometryNRD::trackingState() const {
    if (frames_ == 0) return "waiting for the camera";
    std::string state = "tracking";
    if (!(frame_time_ <= last_tracked_.t)) {
        char text[64];
        std::snprintf(text, sizeof text, "bridging a gap (%.1f s)",
                      std::isnan(last_tracked_.t) ? 0.0 : frame_time_ - last_tracked_.t);
        state = text;
    }
    if (segment_ > 0) state += ", segment " + std::to_string(segment_);
    return state;
}

void VisualOdometryNRD::trackedFrame(const vision::RgbdFrame& frame,
                                     const Eigen::Isometry3d& T_robot_optical) {
    depth_bridge_.reset();
    if (!params_.bridgeByDepth) return;
    last_tracked_frame_ = frame;
    last_tracked_optical_ = T_robot_optical;
}

mrpt::poses::CPose3DPDFGaussian VisualOdometryNRD::lastTrackedHeld() const {
    // (VO's steps since the last node, as a step's: a loose rise held to the carrier's bound -
    // else a gap's edge took VO's 1.4 m sigma in height from the frames before a plain wall)
    auto held = heightHeld(last_tracked_.pdf, params_.stepHeightSigma, params_.edgeCrossCovariance);
    // (as a node's edge: else a gap's edge kept the metre VO's depth-alone steps left loose
    // before it, beside the bridge's own spread)
    if (params_.stepMotionPrior && last_tracked_.t > node_time_)
        held = motionHeld(held, last_tracked_.t - node_time_);
    return held;
}

mrpt::poses::CPose3DPDFGaussian VisualOdometryNRD::motionHeld(
    const mrpt::poses::CPose3DPDFGaussian& edge, double seconds) const {
    // The velocity at this frame (VO's, the edge's end) turned into the last node's axes with
    // the edge's turn; trusted to the model's speed spread only, so that consecutive edges do
    // not each count VO's velocity as known (it came from the edges before).
    const auto& fading = params_.bridgeVelocity;
    const Eigen::Matrix3d R = edge.mean.getRotationMatrix().asEigen();
    const auto v0 = velocityAtLastTracked();
    const double rate = Eigen::AngleAxisd(R).angle() / seconds;
    const Eigen::Vector3d m = R * fading.meanDisplacement(v0.mean, seconds, cruise_.at(rate));
    const Eigen::Matrix3d M =
        R * fading.displacementVariances(seconds, fading.speedSigma).asDiagonal() * R.transpose();
    return translationHeld(edge, m, M, params_.edgeCrossCovariance);
}

mrpt::poses::CPose3DPDFGaussian VisualOdometryNRD::bridge(double gap) const {
    // The last step scaled to the gap (first order in its angles), from the last tracked frame.
    const double k = gap / last_step_seconds_;
    const auto& s = last_step_;
    mrpt::poses::CPose3DPDFGaussian motion;
    motion.mean = mrpt::poses::CPose3D(k * s.x(), k * s.y(), k * s.z(), k * s.yaw(), k * s.pitch(),
                                       k * s.roll());
    const double st = 0.5 * params_.bridgeAccelSigma * gap * gap,
                 sr = 0.5 * params_.bridgeAngularAccelSigma * gap * gap;
    motion.cov.setZero();
    for (int i = 0; i < 3; ++i) {
        motion.cov(i, i) = st * st;
        motion.cov(i + 3, i + 3) = sr * sr;
    }
    mrpt::poses::CPose3DPDFGaussian edge = lastTrackedHeld();
    edge += motion;
    return edge;
}

std::size_t VisualOdometryNRD::windowStart(double seconds) const {
    if (chained_.empty()) return 0;
    const double end = chained_.back().first;
    std::size_t start = chained_.size() - 1;
    while (start > 0 && end - chained_[start].first < seconds) --start;
    return start;
}

VisualOdometryNRD::Velocity VisualOdometryNRD::velocityAtLastTracked() const {
    // Over VO's last tracked frames (from the newest frame that old, else the oldest), not its
    // last step: a step's few millimetres of error in a frame interval are a tenth of a metre
    // per second. And over as long as the motion model carries a velocity on
    // (bridge_velocity_seconds): a hand's sway and bob, a few centimetres at 0.3-2 Hz, are
    // 0.05-0.1 m/s over 0.3 s - carried on for a second, a tenth of a metre sideways at every
    // gap - and average out over the second; the walk persists.
    const std::size_t start = windowStart(params_.bridgeVelocity.correlationSeconds);
    Velocity v;
    if (chained_.empty() || !(chained_.back().first > chained_[start].first)) {
        // (VO has not tracked since it restarted: the velocity the gap before carried, else
        // the carrier's spread)
        if (carried_velocity_) return *carried_velocity_;
        v.sigma = params_.bridgeVelocity.speedSigma;
        v.covariance = v.sigma * v.sigma * Eigen::Matrix3d::Identity();
        return v;
    }
    const auto& [t1, p1] = chained_.back();
    const auto& p0 = chained_[start].second;
    const double dt = t1 - chained_[start].first;
    const Eigen::Matrix3d R1 = p1.getRotationMatrix().asEigen();
    const Eigen::Vector3d d(p1.x() - p0.x(), p1.y() - p0.y(), p1.z() - p0.z());
    v.mean = R1.transpose() * d / dt;
    v.sigma = params_.gravityVelocitySigma;
    // VO's own uncertainty of both ends (each against its reference: at most their sum), as
    // a velocity in the last frame's axes, never below gravityVelocitySigma.
    v.covariance = R1.transpose() * (chained_covariance_.back() + chained_covariance_[start]) * R1 /
                       (dt * dt) +
                   v.sigma * v.sigma * Eigen::Matrix3d::Identity();
    return v;
}

VisualOdometryNRD::Velocity VisualOdometryNRD::turnRateAtLastTracked() const {
    const std::size_t start = windowStart(params_.gravityVelocitySeconds);
    Velocity w;
    if (chained_.empty() || !(chained_.back().first > chained_[start].first)) {
        if (carried_turn_rate_) return *carried_turn_rate_;  // (not tracked since the restart)
        w.sigma = params_.bridgeTurn.rate.speedSigma;
        w.covariance = w.sigma * w.sigma * Eigen::Matrix3d::Identity();
        return w;
    }
    const Eigen::Matrix3d R0 = chained_[start].second.getRotationMatrix().asEigen();
    const Eigen::Matrix3d R1 = chained_.back().second.getRotationMatrix().asEigen();
    const double dt = chained_.back().first - chained_[start].first;
    const Eigen::AngleAxisd turned(R0.transpose() * R1);  // (its axis the same in either frame)
    w.mean = turned.angle() * turned.axis() / dt;
    w.sigma = kTurnRateFloor;
    w.covariance = R1.transpose() *
                       (chained_rotation_covariance_.back() + chained_rotation_covariance_[start]) *
                       R1 / (dt * dt) +
                   w.sigma * w.sigma * Eigen::Matrix3d::Identity();
    return w;
}

bool VisualOdometryNRD::depthTurnKnown() const {
    const double loosest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(depth_bridge_.rotationCovariance())
                               .eigenvalues()
                               .maxCoeff();
    return loosest <= params_.bridgeTurnMaxSigma * params_.bridgeTurnMaxSigma;
}

std::optional<mrpt::poses::CPose3DPDFGaussian> VisualOdometryNRD::bridgeByDepthTurn(double t) const {
    if (!depth_bridge_.active() || !depth_bridge_.turning() ||
        depth_bridge_.startTime() != last_tracked_.t || !(t - last_tracked_.t <= params_.gyroBridgeMaxSeconds))
        return std::nullopt;
    if (!depthTurnKnown()) return std::nullopt;
    const Eigen::Matrix3d turnCovariance = depth_bridge_.rotationCovariance();
    Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
    step.linear() = depth_bridge_.rotation();
    step.translation() = depth_bridge_.displacement();
    Eigen::Matrix<double, 6, 6> cov = Eigen::Matrix<double, 6, 6>::Zero();  // (rotation, translation)
    cov.topLeftCorner<3, 3>() = turnCovariance;
    cov.bottomRightCorner<3, 3>() = depth_bridge_.covariance();
    mrpt::poses::CPose3DPDFGaussian edge = lastTrackedHeld();
    edge += mrpt::poses::CPose3DPDFGaussian(poseOf3D(step), mrptCovarianceOf(cov));
    return edge;
}

std::optional<mrpt::poses::CPose3DPDFGaussian> VisualOdometryNRD::bridgeByGyro(double t) const {
    const auto g = gyro_.between(last_tracked_.t, t);
    if (!g) return std::nullopt;
    const double gap = t - last_tracked_.t;
    // The gyro's body rotation in the robot frame: S R S^T, S the gyro's rotation on the robot.
    const Eigen::Matrix3d S = gyro_.sensorOnRobot().linear();
    Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
    step.linear() = S * g->R * S.transpose();
    Eigen::Matrix<double, 6, 6> cov =
        Eigen::Matrix<double, 6, 6>::Zero();  // (rotation, translation)
    cov.topLeftCorner<3, 3>() = g->sigma * g->sigma * Eigen::Matrix3d::Identity();
    if (params_.bridgeByDepth && depth_bridge_.active() &&
        depth_bridge_.startTime() == last_tracked_.t) {
        // The gap's frames followed up to this one (followGap): the depth's where it pinned.
        step.translation() = depth_bridge_.displacement();
        cov.bottomRightCorner<3, 3>() = depth_bridge_.covariance();
    } else {
        // The velocity before the gap (the last tracked frame's, in its own frame) fading
        // towards the cruise (in the same axes: the gap's turn left out, as for the velocity).
        const auto& fading = params_.bridgeVelocity;
        const auto v0 = velocityAtLastTracked();
        const double rate = Eigen::AngleAxisd(step.linear()).angle() / gap;
        step.translation() = fading.meanDisplacement(v0.mean, gap, cruise_.at(rate));
        cov.bottomRightCorner<3, 3>() = fading.displacementVariances(gap, v0.sigma).asDiagonal();
    }
    mrpt::poses::CPose3DPDFGaussian edge = lastTrackedHeld();
    edge += mrpt::poses::CPose3DPDFGaussian(poseOf3D(step), mrptCovarianceOf(cov));
    return edge;
}

void VisualOdometryNRD::followGap(const vision::RgbdFrame& frame, double t,
                                  const Eigen::Isometry3d& T_robot_optical) {
    if (!params_.bridgeByDepth || !last_tracked_frame_ ||
        !(t - last_tracked_.t <= params_.gyroBridgeMaxSeconds))
        return;
    std::optional<odometry::GyroIntegrator::Rotation> g;
    if (params_.useGyro) g = gyro_.between(last_tracked_.t, t);
    const bool started = depth_bridge_.active() && depth_bridge_.startTime() == last_tracked_.t;
    // A gap is followed one way to its end: the gyro's turn, or where none covered its start
    // the depth's.
    if (started ? (!depth_bridge_.turning() && !g) : (!g && !params_.bridgeTurnByDepth)) return;
    if (!started) {
        // VO's velocity as a measurement of the carrier's, whose spread the motion model knows:
        // where VO's last frames did not measure an axis (a plain wall ahead leaves the height
        // to a few features), the velocity there is the model's, not VO's drift. Axis by axis:
        // VO's correlations between axes are the least sure part of its covariance, and the
        // depth's precise approach would turn a slight one into metres per second elsewhere.
        // (A velocity carried across the gap before is the model's already: taken as it is.)
        // The model's own mean is the cruise (for the turn rate: none).
        const auto weighed = [](const Velocity& m, double spread, const Eigen::Vector3d& prior,
                                Eigen::Vector3d& mean, Eigen::Matrix3d& covariance) {
            if (m.carried) {
                mean = m.mean;
                covariance = m.covariance;
                return;
            }
            const double s2 = spread * spread;
            const Eigen::Array3d c = m.covariance.diagonal().array(), gain = s2 / (s2 + c);
            mean = prior + (gain * (m.mean - prior).array()).matrix();
            covariance = (gain * c).matrix().asDiagonal();
        };
        Eigen::Vector3d v0;
        Eigen::Matrix3d v0Covariance;
        weighed(velocityAtLastTracked(), params_.bridgeVelocity.speedSigma,
                cruise_.at(turnRateAtLastTracked().mean.norm()), v0, v0Covariance);
        // Up: the accelerometer's where measured, else the robot frame's z.
        std::optional<AttitudePrior> up;
        if (params_.useGravity) up = measuredUp(last_tracked_.t);
        depth_bridge_.start(last_tracked_.t, *last_tracked_frame_, last_tracked_optical_, v0,
                            v0Covariance, up ? up->up : Eigen::Vector3d::UnitZ(), cruise_);
        if (!g) {
            // The turn rate the same way: VO's, weighed against a carrier's spread of them.
            Eigen::Vector3d w0;
            Eigen::Matrix3d w0Covariance;
            weighed(turnRateAtLastTracked(), params_.bridgeTurn.rate.speedSigma,
                    Eigen::Vector3d::Zero(), w0, w0Covariance);
            depth_bridge_.startTurn(w0, w0Covariance);
        }
    }
    const int aligned = depth_bridge_.aligned(), rejected = depth_bridge_.rejected(),
              cruising = depth_bridge_.cruising(), beyond = depth_bridge_.beyondCruise();
    if (depth_bridge_.turning()) {
        depth_bridge_.add(t, frame, T_robot_optical);
    } else {
        // The gyro's body rotation in the robot frame: S R S^T, S the gyro's rotation on the robot.
        const Eigen::Matrix3d S = gyro_.sensorOnRobot().linear();
        depth_bridge_.add(t, frame, T_robot_optical, S * g->R * S.transpose());
    }
    depth_bridge_aligned_ += static_cast<std::size_t>(depth_bridge_.aligned() - aligned);
    depth_bridge_rejected_ += static_cast<std::size_t>(depth_bridge_.rejected() - rejected);
    depth_bridge_cruising_ += static_cast<std::size_t>(depth_bridge_.cruising() - cruising);
    depth_bridge_beyond_cruise_ += static_cast<std::size_t>(depth_bridge_.beyondCruise() - beyond);
}

void VisualOdometryNRD::carryAcrossGap(double t) {
    // (the velocity before this gap first: the one the gap before carried, where VO has not
    // tracked since)
    const Velocity before = velocityAtLastTracked();
    carried_velocity_.reset();
    carried_turn_rate_.reset();
    const bool followed = params_.bridgeByDepth && depth_bridge_.active() &&
                          depth_bridge_.startTime() == last_tracked_.t;
    // The gap's turn, into the restart frame's axes: the gyro's, else the depth's.
    std::optional<odometry::GyroIntegrator::Rotation> g;
    if (params_.useGyro) g = gyro_.between(last_tracked_.t, t);
    Eigen::Matrix3d R, turnCovariance;
    if (g) {
        const Eigen::Matrix3d S = gyro_.sensorOnRobot().linear();
        R = S * g->R * S.transpose();
        turnCovariance = g->sigma * g->sigma * Eigen::Matrix3d::Identity();
    } else if (followed && depth_bridge_.turning()) {
        R = depth_bridge_.rotation();
        turnCovariance = depth_bridge_.rotationCovariance();
        if (!depthTurnKnown()) return;  // (as well as a bridge needs it, or not at all)
    } else {
        return;  // (where it turned is not known: nor where its velocity points)
    }
    const auto carried = [](const Eigen::Vector3d& mean, const Eigen::Matrix3d& covariance) {
        Velocity v;
        v.mean = mean;
        v.covariance = covariance;
        v.sigma = std::sqrt(covariance.diagonal().maxCoeff());
        v.carried = true;
        return v;
    };
    // (in the last tracked frame's axes)
    Eigen::Vector3d v = before.mean;
    Eigen::Matrix3d C = before.covariance;
    if (followed) {
        v = depth_bridge_.velocity();
        C = depth_bridge_.velocityCovariance();
    } else {
        const double rate = Eigen::AngleAxisd(R).angle() / (t - last_tracked_.t);
        params_.bridgeVelocity.fadeVelocity(t - last_tracked_.t, v, C, cruise_.at(rate));
    }
    // In the restart frame's axes; the turn's own error turns the velocity too (first order:
    // R exp(theta) sees u = R^T v as u - theta x u).
    const Eigen::Vector3d u = R.transpose() * v;
    const Eigen::Matrix3d ux = vision::skew(u);
    carried_velocity_ = carried(u, R.transpose() * C * R + ux * turnCovariance * ux.transpose());
    ++restarts_carrying_velocity_;
    // Where the depth followed the turn, its rate too (the robot's body rate at t already).
    if (!g) carried_turn_rate_ = carried(depth_bridge_.turnRate(), depth_bridge_.turnRateCovariance());
}

}  // namespace lodestone::graphslam
