#include <lodestone/config/IniSection.h>
#include <lodestone/odometry/FusedOdometry.h>
#include <lodestone/vision/Se3Covariance.h>
#include <lodestone/odometry/RgbdObservationFrame.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <Eigen/Dense>
#include <cmath>

namespace lodestone::odometry {

void FusedOdometry::Params::loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                               const std::string& section) {
    wheels.loadFromConfigFile(source, "wheel_odometry");
    visual.loadFromConfigFile(source, "visual_odometry");
    config::IniSection s(source, section, config::sourceName(source));
    method = s.getString("method", method);
    kalmanWeight = s.getDouble("kalman_weight", kalmanWeight);
    kalmanProcessNoise = s.getDouble("kalman_process_noise", kalmanProcessNoise);
    kalmanMeasurementNoise = s.getDouble("kalman_measurement_noise", kalmanMeasurementNoise);
    encoderLabel = s.getString("encoder_label", encoderLabel);
    cameraLabel = s.getString("camera_label", cameraLabel);
    posePositionNoise = s.getDouble("pose_position_noise", posePositionNoise);
    poseHeadingNoise = s.getDouble("pose_heading_noise", poseHeadingNoise);
    if (!(posePositionNoise > 0)) s.fail("pose_position_noise", "must be > 0");
    if (!(poseHeadingNoise > 0)) s.fail("pose_heading_noise", "must be > 0");
    guidedTiltSigma =
        s.getDouble("guided_tilt_sigma_deg", guidedTiltSigma * 180 / M_PI) * M_PI / 180;
    guidedRiseSigma = s.getDouble("guided_rise_sigma", guidedRiseSigma);
    if (!(guidedTiltSigma >= 0)) s.fail("guided_tilt_sigma_deg", "must be >= 0");
    if (!(guidedRiseSigma >= 0)) s.fail("guided_rise_sigma", "must be >= 0");
    if (kalmanWeight <= 0 || kalmanWeight >= 1) s.fail("kalman_weight", "must be in (0, 1)");
    try {
        makePlanarFusion(method);
    } catch (const std::invalid_argument& e) {
        s.fail("method", e.what());
    }
    s.finish();
}

void FusedOdometry::Params::dumpToTextStream(std::ostream& out) const {
    out << "[wheel_odometry]\n";
    wheels.dumpToTextStream(out);
    out << "[visual_odometry]\n";
    visual.dumpToTextStream(out);
    out << "[odometry_fusion]\nmethod = " << method << "\nkalman_weight = " << kalmanWeight
        << "\nkalman_process_noise = " << kalmanProcessNoise
        << "\nkalman_measurement_noise = " << kalmanMeasurementNoise
        << "\npose_position_noise = " << posePositionNoise
        << "\npose_heading_noise = " << poseHeadingNoise
        << "\nguided_tilt_sigma_deg = " << guidedTiltSigma * 180 / M_PI
        << "\nguided_rise_sigma = " << guidedRiseSigma << "\n";
}

FusedOdometry::FusedOdometry(const Params& params, std::vector<std::string> methods)
    : params_(params),
      method_names_(methods.empty() ? std::vector<std::string>{params.method} : std::move(methods)),
      wheels_(params.wheels),
      visual_(params.visual) {
    for (const auto& m : method_names_) {
        fusions_.push_back(makePlanarFusion(m, params.kalmanWeight, params.kalmanProcessNoise,
                                            params.kalmanMeasurementNoise));
    }
    recent_.resize(fusions_.size());
    prepared_.onlyCamera(params.cameraLabel);
}

std::vector<FusedOdometry::Estimate> FusedOdometry::process(
    const mrpt::obs::CObservation::Ptr& obs) {
    std::vector<Estimate> out;
    if (auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs)) {
        if (!params_.encoderLabel.empty() && odo->sensorLabel != params_.encoderLabel) return out;
        const double t = mrpt::Clock::toDouble(odo->timestamp);
        if (!odo->hasEncodersInfo) {
            out.push_back(fromPoseSample(t, odo->odometry));
            return out;
        }
        if (auto inc = wheels_.addTicks(odo->encoderLeftTicks, odo->encoderRightTicks)) {
            cum_left_ += inc->leftTravel;
            cum_right_ += inc->rightTravel;
        }
        wheel_history_.push_back({t, cum_left_, cum_right_});
        while (wheel_history_.size() > 2 && wheel_history_[1].t < t - 5.0)
            wheel_history_.pop_front();
        while (!pending_.empty() && pending_.front().t <= t) {
            out.push_back(resolve(pending_.front()));
            pending_.pop_front();
        }
    } else if (auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs)) {
        if (!params_.cameraLabel.empty() && scan->sensorLabel != params_.cameraLabel) return out;
        if (pose_samples_ > 0) {
            ++frames_ignored_;
            return out;
        }
        vision::PreparedFrame frame = prepared_.take(*scan);
        const double t = frame.frame.timestamp;
        const Eigen::Isometry3d T_robot_optical = opticalFrameOnRobot(scan->sensorPose);
        const auto prior = wheelPrior(t, T_robot_optical);
        Pending p{t, visual_.process(std::move(frame), prior ? &*prior : nullptr), T_robot_optical};
        scan->unload();
        pending_.push_back(std::move(p));
        ++frames_;
    }
    return out;
}

std::vector<FusedOdometry::Estimate> FusedOdometry::flush() {
    std::vector<Estimate> out;
    while (!pending_.empty()) {
        out.push_back(resolve(pending_.front()));
        pending_.pop_front();
    }
    return out;
}

Eigen::Vector2d FusedOdometry::travelAt(double t) const {
    if (wheel_history_.empty()) return {0, 0};
    if (t <= wheel_history_.front().t)
        return {wheel_history_.front().left, wheel_history_.front().right};
    for (std::size_t i = 1; i < wheel_history_.size(); ++i) {
        const auto& a = wheel_history_[i - 1];
        const auto& b = wheel_history_[i];
        if (t <= b.t) {
            const double f = b.t > a.t ? (t - a.t) / (b.t - a.t) : 1.0;
            return {a.left + f * (b.left - a.left), a.right + f * (b.right - a.right)};
        }
    }
    return {wheel_history_.back().left, wheel_history_.back().right};
}

std::optional<vision::MotionPrior> FusedOdometry::wheelPrior(
    double t, const Eigen::Isometry3d& T_robot_optical) const {
    // Beyond this the wheels are silent (unplugged, a lift): no prediction.
    constexpr double kMaxExtrapolation = 0.1;  // [s]
    const auto reference = visual_.referenceTimestamp();
    if (!reference || wheel_history_.size() < 2 || *reference < wheel_history_.front().t)
        return std::nullopt;
    const auto& last = wheel_history_.back();
    const auto& before = wheel_history_[wheel_history_.size() - 2];
    const double ahead = t - last.t;
    if (ahead > kMaxExtrapolation) return std::nullopt;
    Eigen::Vector2d now = travelAt(t);
    Eigen::Vector2d extrapolated{0, 0};  // each wheel's travel assumed past the last sample
    if (ahead > 0 && last.t > before.t) {
        extrapolated = Eigen::Vector2d(last.left - before.left, last.right - before.right) *
                       (ahead / (last.t - before.t));
        now += extrapolated;
    }
    const Eigen::Vector2d d = now - travelAt(*reference);
    const auto step = DiffDriveOdometry::stepFromOrigin(d[0], d[1], params_.wheels);
    // Robot frame, twist order (w, v): the planar step's covariance, the floor's tilt and rise,
    // and the extrapolation wholly uncertain (the robot may have stopped).
    Eigen::Matrix<double, 6, 6> C = Eigen::Matrix<double, 6, 6>::Zero();
    const int idx[3] = {3, 4, 2};  // (x, y, yaw) -> (v_x, v_y, w_z)
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) C(idx[i], idx[j]) = step.cov(i, j);
    }
    const double e2 = extrapolated.squaredNorm();
    C(3, 3) += e2;
    C(4, 4) += e2;
    C(2, 2) += e2 / (params_.wheels.wheelBase * params_.wheels.wheelBase);
    C(0, 0) = C(1, 1) = params_.guidedTiltSigma * params_.guidedTiltSigma;
    C(5, 5) = params_.guidedRiseSigma * params_.guidedRiseSigma;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(step.mean.phi(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(step.mean.x(), step.mean.y(), 0);
    // Into the optical frame: A^-1 exp(xi) T A = exp(Ad(A^-1) xi) A^-1 T A.
    const Eigen::Isometry3d Ainv = T_robot_optical.inverse();
    const Eigen::Matrix<double, 6, 6> Ad = vision::adjoint(Ainv);
    vision::MotionPrior prior;
    prior.T_ref_cur = Ainv * T * T_robot_optical;
    prior.covariance = Ad * C * Ad.transpose();
    return prior;
}

mrpt::poses::CPosePDFGaussian FusedOdometry::visualOnRobot(const Pending& p, double* rise,
                                                          double* riseVariance) const {
    // Robot-frame motion: A T A^-1, with A the optical frame on the robot.
    const Eigen::Isometry3d& A = p.T_robot_optical;
    const Eigen::Isometry3d T = A * p.vo.T_ref_cur * A.inverse();
    // Covariance of a left perturbation moves with the adjoint of A.
    const Eigen::Matrix<double, 6, 6> Ad = vision::adjoint(A);
    const Eigen::Matrix<double, 6, 6> C = Ad * p.vo.covariance * Ad.transpose();
    const int idx[3] = {3, 4, 2};  // (x, y, yaw) = (v_x, v_y, w_z)
    mrpt::poses::CPosePDFGaussian m;
    m.mean = mrpt::poses::CPose2D(T.translation().x(), T.translation().y(),
                                  std::atan2(T.linear()(1, 0), T.linear()(0, 0)));
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) m.cov(i, j) = C(idx[i], idx[j]);
    }
    if (rise) *rise = T.translation().z();
    if (riseVariance) *riseVariance = C(5, 5);
    return m;
}

FusedOdometry::Estimate FusedOdometry::fromPoseSample(double t, const mrpt::poses::CPose2D& pose) {
    Estimate e;
    e.timestamp = t;
    mrpt::poses::CPosePDFGaussian increment;  // zero on the first sample
    if (last_pose_sample_) {
        increment.mean = pose - *last_pose_sample_;
        increment.cov.setZero();
        increment.cov(0, 0) = increment.cov(1, 1) = params_.posePositionNoise;
        increment.cov(2, 2) = params_.poseHeadingNoise;
        pose_estimate_ += increment;
    }
    last_pose_sample_ = pose;
    ++pose_samples_;
    // No fusion: the source is already an odometry; every method reports it.
    e.poses.assign(fusions_.size(), pose_estimate_);
    e.increments.assign(fusions_.size(), increment);
    e.wheelScale.assign(fusions_.size(), Eigen::Matrix<double, 3, 2>::Zero());
    e.wheel = increment;  // the base's own odometry plays the encoders' part
    return e;
}

FusedOdometry::Estimate FusedOdometry::resolve(const Pending& p) {
    Estimate e;
    e.timestamp = p.t;
    e.visual = p.vo;
    // VO's reference from now on is this frame's reference, or this frame when VO (re)started
    // on it (no reference then): older frames are never needed again.
    oldest_reference_ = p.vo.referenceTimestamp > 0 ? p.vo.referenceTimestamp : p.t;
    const Eigen::Vector2d travel = travelAt(p.t);
    const bool first = !last_frame_time_;
    Eigen::Matrix<double, 3, 2> scale = Eigen::Matrix<double, 3, 2>::Zero();
    if (first) {
        for (auto& f : fusions_) f->reset({});
    } else {
        OdometryStep step;
        step.dt = p.t - *last_frame_time_;
        const Eigen::Vector2d d = travel - last_frame_travel_;
        step.wheel = DiffDriveOdometry::stepFromOrigin(d[0], d[1], params_.wheels);
        scale = DiffDriveOdometry::scaleJacobian(d[0], d[1], params_.wheels);
        const bool visualMotion = p.vo.success;
        const auto robotMotion = visualMotion
                                     ? visualOnRobot(p, &e.visualRise, &e.visualRiseVariance)
                                     : mrpt::poses::CPosePDFGaussian();
        e.wheel = step.wheel;
        if (visualMotion) e.visualSinceReference = robotMotion;
        for (std::size_t m = 0; m < fusions_.size(); ++m) {
            OdometryStep s = step;
            if (visualMotion) {
                // Re-base: VO says where the robot is relative to where it was at the reference
                // frame; express that from this method's pose at the previous frame. (Kalman's
                // visual track takes the same step: an approximation when frames failed.)
                const auto ref = recent_[m].find(p.vo.referenceTimestamp);
                if (ref != recent_[m].end()) {
                    mrpt::poses::CPosePDFGaussian v = robotMotion;
                    v.mean = (ref->second - fusions_[m]->pose().mean) + robotMotion.mean;
                    s.visual = v;
                }
            }
            fusions_[m]->step(s);
        }
    }
    for (std::size_t m = 0; m < fusions_.size(); ++m) {
        e.poses.push_back(fusions_[m]->pose());
        e.increments.push_back(first ? mrpt::poses::CPosePDFGaussian()
                                     : fusions_[m]->lastIncrement());
        e.wheelScale.push_back(fusions_[m]->lastWheelGain() * scale);  // (zero on the first)
        recent_[m][p.t] = fusions_[m]->pose().mean;
        // Only frames VO may still use as its reference are kept.
        while (!recent_[m].empty() && recent_[m].begin()->first < oldest_reference_) {
            recent_[m].erase(recent_[m].begin());
        }
    }
    last_frame_time_ = p.t;
    last_frame_travel_ = travel;
    return e;
}

}  // namespace lodestone::odometry
