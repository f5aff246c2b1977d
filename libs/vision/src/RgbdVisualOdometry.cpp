#include <lodestone/vision/JoinRotation.h>
#include <lodestone/vision/RgbdVisualOdometry.h>

#include <algorithm>
#include <chrono>
#include <optional>

namespace lodestone::vision {

namespace {
double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

RgbdVisualOdometry::RgbdVisualOdometry() : RgbdVisualOdometry(Params()) {}

namespace {
GuidedMatcher::Params guidedParams(const RgbdVisualOdometry::Params& p) {
    GuidedMatcher::Params g;
    g.gateChi2 = p.guidedGateChi2;
    g.keypointSigma = p.guidedKeypointSigma;
    g.scaleFactor = p.orb.scaleFactor;
    g.pointNoise = p.ransac.pointNoise;
    g.depthNoise = p.ransac.depthNoise;
    g.maxDistance = p.matcher.maxDistance;
    g.ratio = p.matcher.ratio;
    g.crossCheck = p.matcher.crossCheck;
    return g;
}
}  // namespace

RgbdVisualOdometry::RgbdVisualOdometry(const Params& params)
    : params_(params),
      matcher_(params.matcher),
      guided_(guidedParams(params)),
      ransac_(params.ransac),
      icp_(params.depthIcp),
      depth_model_(params.depthModelKeyframes) {}

std::optional<double> RgbdVisualOdometry::referenceTimestamp() const {
    if (!reference_ || state_ == VoState::Lost) return std::nullopt;
    return reference_time_;
}

void RgbdVisualOdometry::reset() {
    reference_.reset();
    depth_model_.clear();
    failures_ = 0;
    state_ = VoState::Initializing;
}

RgbdVisualOdometry::Alignment RgbdVisualOdometry::align(const FrameFeatures& reference,
                                                        const FrameFeatures& current,
                                                        std::uint64_t seed) const {
    Alignment a;
    if (current.size() < static_cast<std::size_t>(params_.ransac.minInliers) ||
        reference.size() < static_cast<std::size_t>(params_.ransac.minInliers)) {
        a.failure = VoFailure::FewFeatures;
        return a;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const auto matches = matcher_.match(current.descriptors, reference.descriptors);
    const double matching = msSince(t0);
    a = alignMatches(reference, current, matches, seed);
    a.timing.matching = matching;
    return a;
}

RgbdVisualOdometry::Alignment RgbdVisualOdometry::alignMatches(
    const FrameFeatures& reference, const FrameFeatures& current,
    const std::vector<cv::DMatch>& matches, std::uint64_t seed) const {
    Alignment a;
    a.matches = matches.size();
    if (matches.size() < static_cast<std::size_t>(params_.ransac.minInliers)) {
        a.failure = VoFailure::FewMatches;
        return a;
    }
    const auto t0 = std::chrono::steady_clock::now();
    Eigen::Matrix3Xd src(3, matches.size()), dst(3, matches.size());
    for (std::size_t i = 0; i < matches.size(); ++i) {
        src.col(static_cast<Eigen::Index>(i)) =
            current.points.col(matches[i].queryIdx).cast<double>();
        dst.col(static_cast<Eigen::Index>(i)) =
            reference.points.col(matches[i].trainIdx).cast<double>();
    }
    a.estimate = ransac_.estimate(src, dst, seed);
    a.timing.ransac = msSince(t0);
    a.inliers = a.estimate.inliers.size();
    a.success = a.estimate.success;
    if (!a.success) a.failure = VoFailure::NoConsensus;
    return a;
}

VoFailure RgbdVisualOdometry::plausibility(const RigidEstimate& est, double timestamp) const {
    const double angle = Eigen::AngleAxisd(est.transform.rotation()).angle();
    if (est.transform.translation().norm() > params_.maxTranslation || angle > params_.maxRotation)
        return VoFailure::Implausible;
    // The step from the last tracked frame (both in the reference): what the carrier did in
    // the time between them, give or take one step's error.
    const double dt = std::max(0.0, timestamp - last_time_);
    const Eigen::Isometry3d step = last_in_ref_.inverse() * est.transform;
    if (params_.maxSpeed > 0 &&
        step.translation().norm() > params_.maxSpeed * dt + params_.stepError)
        return VoFailure::FasterThanCarrier;
    if (params_.maxTurnRate > 0 && Eigen::AngleAxisd(step.rotation()).angle() >
                                       params_.maxTurnRate * dt + params_.stepErrorAngle)
        return VoFailure::FasterThanCarrier;
    return VoFailure::None;
}

bool RgbdVisualOdometry::replaceIfPlausible(RigidEstimate& est, const Eigen::Isometry3d& T,
                                            const Eigen::Matrix<double, 6, 6>& covariance,
                                            double timestamp) const {
    RigidEstimate candidate = est;
    candidate.transform = T;
    candidate.covariance = covariance;
    if (plausibility(candidate, timestamp) != VoFailure::None) return false;
    est = candidate;
    return true;
}

PreparedFrame RgbdVisualOdometry::prepare(RgbdFrame frame) const {
    PreparedFrame p;
    p.frame = std::move(frame);
    auto t0 = std::chrono::steady_clock::now();
    // (an extractor of its own: OpenCV's ORB is not documented as safe to share across threads)
    p.features = OrbExtractor(params_.orb).extract(p.frame);
    p.orbMs = msSince(t0);
    if (params_.depthAlignment) {
        t0 = std::chrono::steady_clock::now();
        p.cloud = sampleDepthCloud(p.frame, params_.depthSampling);
        p.cloudMs = msSince(t0);
    }
    return p;
}

VoResult RgbdVisualOdometry::process(const RgbdFrame& frame, const MotionPrior* prior,
                                     const RotationPrior* rotation) {
    return process(prepare(frame), prior, rotation);
}

VoResult RgbdVisualOdometry::process(PreparedFrame prepared, const MotionPrior* prior,
                                     const RotationPrior* rotation) {
    VoResult r = processFrame(prepared, prior, rotation);
    ++totals_.frames;
    if (r.guided) ++totals_.guided;
    totals_.ms.orb += r.timing.orb;
    totals_.ms.matching += r.timing.matching;
    totals_.ms.ransac += r.timing.ransac;
    totals_.ms.depth += r.timing.depth;
    if (r.depthAligned) ++totals_.depthAligned;
    if (r.depthJoined) ++totals_.depthJoined;
    if (r.depthJoined && r.depthDisagreed) ++totals_.depthJoinedDisagreeing;
    return r;
}

bool RgbdVisualOdometry::isKeyframe(const Eigen::Isometry3d& measured,
                                    const MotionPrior* prior,
                                    const RotationPrior* rotation) const {
    const auto beyond = [&](const Eigen::Isometry3d& T, double factor) {
        return T.translation().norm() >= factor * params_.keyframeDistance ||
               Eigen::AngleAxisd(T.rotation()).angle() >= factor * params_.keyframeAngle;
    };
    if (params_.keyframeBy == Params::KeyframeBy::Measured) return beyond(measured, 1);
    // Chosen on what was known before this frame was measured, so its own error does not
    // choose it (that would keep the frames whose error lengthens their step): the prior, else
    // the last tracked frame's motion - one frame late (constant velocity from it adds the
    // last step's noise: a fifth to twice as many keyframes, measured).
    Eigen::Isometry3d predicted = prior ? prior->T_ref_cur : last_in_ref_;
    if (rotation) predicted.linear() = rotation->R_ref_cur;
    return beyond(predicted, 1) || beyond(measured, 2);
}

Eigen::Isometry3d RgbdVisualOdometry::constantVelocity(double timestamp) const {
    if (!(last_step_dt_ > 0)) return last_in_ref_;
    // The last step scaled to the time since the last tracked frame (at most 5 steps' worth).
    const double k = std::clamp((timestamp - last_time_) / last_step_dt_, 0.0, 5.0);
    const Eigen::AngleAxisd turn(last_step_.rotation());
    Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
    step.linear() = Eigen::AngleAxisd(k * turn.angle(), turn.axis()).toRotationMatrix();
    step.translation() = k * last_step_.translation();
    return last_in_ref_ * step;
}

void RgbdVisualOdometry::trackedAt(const Eigen::Isometry3d& T_ref_cur, double timestamp,
                                   bool becameReference, bool measured, double velocitySeconds) {
    last_step_ = last_in_ref_.inverse() * T_ref_cur;
    last_step_dt_ = timestamp - last_time_;
    if (measured && timestamp > reference_time_) {
        // Over the whole stretch since the reference: a frame's own step is too short to say.
        velocity_ = T_ref_cur.translation() / (timestamp - reference_time_);
    } else if (last_step_dt_ > 0) {
        velocity_ *= std::exp(-last_step_dt_ / velocitySeconds);
    }
    if (becameReference) velocity_ = T_ref_cur.linear().transpose() * velocity_;
    last_time_ = timestamp;
    last_in_ref_ = becameReference ? Eigen::Isometry3d::Identity() : T_ref_cur;
}

DepthAlignment RgbdVisualOdometry::alignDepth(const DepthCloud& cloud, double timestamp,
                                              const MotionPrior* prior,
                                              const RotationPrior* rotation) const {
    Eigen::Isometry3d initial = prior ? prior->T_ref_cur : constantVelocity(timestamp);
    // Where the depth does not pin it, the carrier went on as its velocity fades (not constant
    // velocity: a walker stops to turn, and a step's velocity turns with the camera). Not the
    // last step's: a depth-aligned step's motion along what the depth left loose is where the
    // alignment started, so each such step would start the next - along a plain corridor the
    // steps grew frame by frame to the carrier's speed bound (docs/results/camera-only.md).
    const double tau = rotation ? rotation->velocitySeconds : 1.0,
                 dt = std::max(0.0, timestamp - last_time_);
    if (!prior)
        initial.translation() =
            last_in_ref_.translation() - velocity_ * (tau * std::expm1(-dt / tau));
    // The gyro's rotation starts the alignment (a turn in front of a wall is what constant
    // velocity gets wrong).
    if (rotation) initial.linear() = rotation->R_ref_cur;
    if (!rotation || !(rotation->translationSigma > 0) || params_.gyroDepthMinObserved == 0)
        return icp_.align(depth_model_, cloud, initial);
    // The rotation measured, the translation as loose as the carrier allows: solved with the
    // depth, which then need pin only what the rotation leaves (a wall's distance).
    MotionPrior measured;
    measured.T_ref_cur = initial;
    measured.T_ref_cur.translation() = last_in_ref_.translation() - velocity_ * (tau * std::expm1(-dt / tau));
    measured.covariance.setZero();
    measured.covariance.topLeftCorner<3, 3>().diagonal().setConstant(rotation->sigma * rotation->sigma);
    measured.covariance.bottomRightCorner<3, 3>().diagonal().setConstant(
        rotation->translationSigma * rotation->translationSigma);
    DepthAlignment d = icp_.align(depth_model_, cloud, initial, &measured);
    if (d.success && d.observed < params_.gyroDepthMinObserved) {
        d.success = false;
        d.failure = DepthAlignFailure::Unobservable;
    }
    return d;
}

VoResult RgbdVisualOdometry::processFrame(PreparedFrame& prepared, const MotionPrior* prior,
                                          const RotationPrior* rotation) {
    VoResult r;
    ++frame_count_;
    const RgbdFrame& frame = prepared.frame;
    FrameFeatures& current = prepared.features;
    r.timing.orb = prepared.orbMs;
    r.features = current.size();
    r.frameFeatures = std::make_shared<const FrameFeatures>(current);
    // The frame's depth points, sampled ahead or when first needed: for a new reference, a
    // start, or an alignment (most frames whose features align need none unless solved with
    // them). Their cost counts where they are used.
    bool cloudCounted = false;
    const DepthCloudSource cloud = [&]() -> DepthCloud& {
        if (!prepared.cloud) {
            const auto td = std::chrono::steady_clock::now();
            prepared.cloud = sampleDepthCloud(frame, params_.depthSampling);
            prepared.cloudMs = msSince(td);
        }
        if (!cloudCounted) r.timing.depth += prepared.cloudMs;
        cloudCounted = true;
        return *prepared.cloud;
    };
    const auto fail = [&](VoFailure why) {
        r.failure = why;
        if (state_ != VoState::Lost && ++failures_ >= params_.lostAfter) state_ = VoState::Lost;
        r.state = state_;
        return r;
    };

    if (state_ == VoState::Lost || !reference_) {
        // Nothing to start from either: that too counts towards LOST.
        if (!startFrom(current, frame.timestamp, cloud)) return fail(VoFailure::FewFeatures);
        r.state = state_;
        r.failure = VoFailure::NoReference;
        return r;
    }
    r.referenceTimestamp = reference_time_;
    const Alignment aligned = matchFeatures(current, frame, prior, params_.seed + frame_count_, r);
    r.matches = aligned.matches;
    r.inliers = aligned.inliers;
    RigidEstimate est = aligned.estimate;
    const VoFailure implausible =
        aligned.success ? plausibility(est, frame.timestamp) : VoFailure::None;
    if (!aligned.success || implausible != VoFailure::None) {
        r.failure = aligned.success ? implausible : aligned.failure;
        if (!params_.depthAlignment) return fail(r.failure);
        // The features failed; the depth may still hold walls, a floor, a door frame.
        if (!alignByDepthAlone(cloud(), frame.timestamp, prior, rotation, est, r))
            return fail(r.failure);
    } else if (params_.depthAlignment && params_.depthWithFeatures) {
        joinDepth(cloud(), frame.timestamp, est, r);
    }
    r.T_ref_cur_camera = est.transform;
    r.covariance_camera = est.covariance;
    joinGyro(rotation, frame.timestamp, est, r);
    const bool keyframe = isKeyframe(est.transform, prior, rotation);
    r.success = true;
    r.T_ref_cur = est.transform;
    r.covariance = est.covariance;
    failures_ = 0;
    state_ = VoState::Tracking;
    r.state = state_;
    trackedAt(est.transform, frame.timestamp, keyframe, !r.depthAligned,
              rotation ? rotation->velocitySeconds : 1.0);
    if (keyframe) {
        becomeReference(current, frame.timestamp, est.transform,
                        !r.depthAligned || r.depthObserved == 6, cloud);
    }
    return r;
}

void RgbdVisualOdometry::becomeReference(FrameFeatures& features, double timestamp,
                                         const Eigen::Isometry3d& T_ref_new, bool pinned,
                                         const DepthCloudSource& cloud) {
    reference_ = std::move(features);
    reference_time_ = timestamp;
    if (params_.depthAlignment) depth_model_.addReference(std::move(cloud()), T_ref_new.inverse(), pinned);
}

bool RgbdVisualOdometry::startFrom(FrameFeatures& features, double timestamp,
                                   const DepthCloudSource& cloud) {
    // (Re-)initialize on a frame good enough to track from.
    // A frame with too few features may still start depth alignment (depth_start): a plain
    // corridor's walls and floor pin its heading and its place across, the wheels the rest
    // (the next frame decides whether the depth pins enough, depth_min_observed).
    const bool depthToStartFrom = params_.depthAlignment && params_.depthStart &&
                                  cloud().size() >= params_.depthIcp.minCorrespondences;
    if (features.size() < static_cast<std::size_t>(params_.ransac.minInliers) && !depthToStartFrom)
        return false;
    depth_model_.clear();
    becomeReference(features, timestamp, Eigen::Isometry3d::Identity(), true, cloud);
    last_in_ref_.setIdentity();
    last_time_ = timestamp;
    last_step_dt_ = 0;
    velocity_.setZero();
    failures_ = 0;
    state_ = VoState::Initializing;
    return true;
}

RgbdVisualOdometry::Alignment RgbdVisualOdometry::matchFeatures(const FrameFeatures& current,
                                                                const RgbdFrame& frame,
                                                                const MotionPrior* prior,
                                                                std::uint64_t seed, VoResult& r) {
    std::optional<Alignment> aligned;
    if (prior && params_.guidedMatching && current.size() > 0) {
        // Guided first; a prior the frame contradicts (slip, a lift) leaves too few matches or
        // an implausible motion, and brute force decides instead.
        const auto tg = std::chrono::steady_clock::now();
        const auto g = guided_.match(current, *reference_, frame.intrinsics, *prior);
        const double matching = msSince(tg);
        totals_.guidedPairsCompared += static_cast<double>(g.compared);
        totals_.guidedPairsAll += static_cast<double>(current.size() * reference_->size());
        auto a = alignMatches(*reference_, current, g.matches, seed);
        a.timing.matching = matching;
        if (a.success && plausibility(a.estimate, frame.timestamp) == VoFailure::None) {
            aligned = a;
            r.guided = true;
        } else {
            ++totals_.guidedFallback;
            r.timing.matching += a.timing.matching;
            r.timing.ransac += a.timing.ransac;
        }
    }
    if (!aligned) aligned = align(*reference_, current, seed);
    r.timing.matching += aligned->timing.matching;
    r.timing.ransac += aligned->timing.ransac;
    return *aligned;
}

bool RgbdVisualOdometry::alignByDepthAlone(const DepthCloud& points, double timestamp,
                                           const MotionPrior* prior, const RotationPrior* rotation,
                                           RigidEstimate& est, VoResult& r) {
    const auto td = std::chrono::steady_clock::now();
    ++totals_.depthTried;
    const DepthAlignment d = alignDepth(points, timestamp, prior, rotation);
    r.timing.depth += msSince(td);
    r.depthObserved = d.observed;
    est.transform = d.T_ref_cur;
    est.covariance = d.covariance;
    ++totals_.depthObserved[static_cast<std::size_t>(std::clamp(d.observed, 0, 6))];
    if (!d.success || plausibility(est, timestamp) != VoFailure::None) {
        ++totals_.depthFailures[static_cast<std::size_t>(d.failure)];
        return false;
    }
    r.depthAligned = true;
    return true;
}

void RgbdVisualOdometry::joinDepth(const DepthCloud& points, double timestamp, RigidEstimate& est,
                                   VoResult& r) {
    // Both measured the motion: one solve, the features' covariance as a measurement.
    const auto td = std::chrono::steady_clock::now();
    MotionPrior measured;
    measured.T_ref_cur = est.transform;
    measured.covariance = est.covariance;
    const DepthAlignment d = icp_.align(depth_model_, points, est.transform, &measured);
    r.timing.depth += msSince(td);
    if (d.success && replaceIfPlausible(est, d.T_ref_cur, d.covariance, timestamp)) {
        r.depthJoined = true;
        r.depthObserved = d.observed;
        r.depthDisagreed = d.disagreed;
    }
}

void RgbdVisualOdometry::joinGyro(const RotationPrior* rotation, double timestamp,
                                  RigidEstimate& est, VoResult& r) const {
    const bool tilt = params_.gyroWithFeatures == Params::GyroJoin::Tilt;
    if (!rotation || params_.gyroWithFeatures == Params::GyroJoin::Off || r.depthAligned ||
        (tilt && !(rotation->vertical.norm() > 0)))
        return;
    // (where the depth alone aligned, the rotation already started and measured it)
    const MotionPrior joined =
        joinRotation({est.transform, est.covariance}, rotation->R_ref_cur, rotation->sigma,
                     tilt ? rotation->vertical : Eigen::Vector3d::Zero());
    r.gyroJoined = replaceIfPlausible(est, joined.T_ref_cur, joined.covariance, timestamp);
}

}  // namespace lodestone::vision
