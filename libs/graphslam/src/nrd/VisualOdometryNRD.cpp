#include <lodestone/graphslam/Se3Pose.h>
#include <lodestone/graphslam/gso/PoseGraphSolver.h>
#include <lodestone/graphslam/nrd/KeyframeCloud.h>
#include <lodestone/graphslam/nrd/VisualOdometryNRD.h>
#include <lodestone/odometry/RgbdObservationFrame.h>
#include <lodestone/vision/Se3Covariance.h>

#include <cmath>

#include "VoTimingJson.h"

namespace lodestone::graphslam {

namespace {
/** VO's motion (optical frame, reference <- current) as the robot's, with its covariance:
 * A T A^-1, the covariance of a perturbation moved with the adjoint of A. */
mrpt::poses::CPose3DPDFGaussian robotMotion(const vision::VoResult& r, const Eigen::Isometry3d& A) {
    const Eigen::Isometry3d T = A * r.T_ref_cur * A.inverse();
    const Eigen::Matrix<double, 6, 6> Ad = vision::adjoint(A);
    return mrpt::poses::CPose3DPDFGaussian(poseOf3D(T),
                                           mrptCovarianceOf(Ad * r.covariance * Ad.transpose()));
}

double rotationAngle(const mrpt::poses::CPose3D& p) {
    return Eigen::AngleAxisd(p.getRotationMatrix().asEigen()).angle();
}

/** An edge from a composed motion: its information, floored so a still camera's (zero)
 * covariance stays invertible. */
Constraint edgeOf(const mrpt::poses::CPose3DPDFGaussian& pdf, bool crossCovariance) {
    Constraint c;
    c.mean = pdf.mean;
    auto cov = pdf.cov;
    for (int k = 0; k < 6; ++k) cov(k, k) += 1e-10;
    if (!crossCovariance) {  // (MRPT's order: x, y, z, then yaw, pitch, roll)
        for (int a = 0; a < 3; ++a)
            for (int b = 3; b < 6; ++b) cov(a, b) = cov(b, a) = 0;
    }
    c.cov_inv = cov.inverse_LLt();
    return c;
}
}  // namespace

VisualOdometryNRD::VisualOdometryNRD() : vo_(params_.visual) { setClassName("VisualOdometryNRD"); }

void VisualOdometryNRD::configure(const mrpt::config::CConfigFileBase& ini) {
    Params p = params_;  // all or nothing
    p.loadFrom(ini);
    params_ = p;
    vo_ = vision::RgbdVisualOdometry(params_.visual);
    prepared_.onlyCamera(params_.cameraLabel);
    gyro_ = odometry::GyroIntegrator(params_.gyro);
    gyro_bias_ = odometry::GyroBiasEstimator(params_.gyro.biasStd);
    gravity_ = odometry::GravityEstimator(params_.gravity);
    floor_ = LevelFloor(params_.floor);
    odometry::DepthBridge::Params bridge;
    bridge.motion = params_.bridgeVelocity;
    bridge.sampling = params_.visual.depthSampling;
    bridge.icp = params_.visual.depthIcp;
    bridge.heightSigma = params_.bridgeHeightSigma;
    bridge.turn = params_.bridgeTurn;
    depth_bridge_ = odometry::DepthBridge(bridge);
    cruise_ = odometry::CruiseVelocity(params_.bridgeCruiseSeconds, kTurnRateFloor);
}

bool VisualOdometryNRD::updateState(mrpt::obs::CActionCollection::Ptr,
                                    mrpt::obs::CSensoryFrame::Ptr observations,
                                    mrpt::obs::CObservation::Ptr observation) {
    just_registered_.reset();
    const auto take = [&](const mrpt::obs::CObservation::Ptr& o) {
        // (one node per call, the engine's contract: in a sensory frame holding two RGB-D
        // frames, a frame after a new node is skipped - rawlogs of observations give one a call)
        if (auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(o);
            scan && !just_registered_) {
            consume(scan);
        } else if (auto imu = std::dynamic_pointer_cast<mrpt::obs::CObservationIMU>(o);
                   imu && params_.useGyro) {
            consumeGyro(*imu);
        }
    };
    if (observation) take(observation);
    if (observations) {
        for (const auto& o : *observations) take(o);
    }
    return just_registered_.has_value();
}

void VisualOdometryNRD::consumeGyro(const mrpt::obs::CObservationIMU& imu) {
    if (params_.gyroLabel.empty() && imu.has(mrpt::obs::IMU_WZ))
        params_.gyroLabel = imu.sensorLabel;
    if (imu.sensorLabel != params_.gyroLabel) return;
    gyro_.add(imu);
    if (params_.useGravity) gravity_.add(imu);
}

std::optional<vision::RotationPrior> VisualOdometryNRD::gyroSinceReference(
    double t, const Eigen::Isometry3d& T_robot_optical) const {
    const auto since = vo_.referenceTimestamp();
    if (!since) return std::nullopt;
    const auto r = gyro_.between(*since, t);
    if (!r) return std::nullopt;
    // The gyro's body rotation seen in the optical frame: C^T R C, C the optical frame's
    // rotation in the gyro's.
    const Eigen::Matrix3d C = gyro_.sensorOnRobot().linear().transpose() * T_robot_optical.linear();
    // How far the carrier may have gone meanwhile: the fading velocity's spread over the time.
    const auto& fading = params_.bridgeVelocity;
    // The vertical, where the accelerometer's up holds the tilt at each node (VO's
    // gyro_with_features = tilt): the robot's z in the optical frame (a hand-held camera is the
    // robot, level to a few degrees).
    Eigen::Vector3d vertical = Eigen::Vector3d::Zero();
    if (params_.useGravity) vertical = T_robot_optical.linear().transpose() * Eigen::Vector3d::UnitZ();
    return vision::RotationPrior{C.transpose() * r->R * C, r->sigma,
                                 std::sqrt(fading.displacementVariance(t - *since)),
                                 fading.correlationSeconds, vertical};
}

void VisualOdometryNRD::consume(const mrpt::obs::CObservation3DRangeScan::Ptr& scan) {
    if (params_.cameraLabel.empty()) {
        params_.cameraLabel = scan->sensorLabel;
        prepared_.onlyCamera(params_.cameraLabel);  // (another camera's frames: not ahead)
    }
    if (scan->sensorLabel != params_.cameraLabel) return;
    ++frames_;
    const double t = mrpt::Clock::toDouble(scan->timestamp);
    frame_time_ = t;
    const auto T_robot_optical = odometry::opticalFrameOnRobot(scan->sensorPose);
    std::optional<vision::RotationPrior> rotation;
    if (params_.useGyro) {
        rotation = gyroSinceReference(t, T_robot_optical);
        if (rotation) ++gyro_priors_;
    }
    vision::PreparedFrame prepared = prepared_.take(*scan);
    const vision::RgbdFrame frame = prepared.frame;  // (the images shared, not copied)
    // (for the floor, should this frame be a node)
    if (params_.floorLevel) {
        frame_ = frame;
        frame_cloud_ = prepared.cloud;
    }
    const auto r = vo_.process(std::move(prepared), nullptr, rotation ? &*rotation : nullptr);
    if (params_.useGyro) dropGyroBefore(t);
    // (from the features' steps only: where the depth alone aligned, the gyro started it)
    if (params_.useGyro && r.success && !r.depthAligned && vo_.referenceTimestamp() == t)
        learnGyroBias(r, t, T_robot_optical);
    const mrpt::poses::CPose3DPDFGaussian here;  // a frame at the new node: identity, certain
    if (r.failure == vision::VoFailure::NoReference) {
        restartAt(*scan, t, r, frame, T_robot_optical);
        return;
    }
    if (!r.success) {
        ++failed_frames_;  // (VO keeps its reference; once LOST it restarts: NoReference above)
        ++failures_[vision::toString(r.failure)];
        if (params_.useGyro || params_.bridgeTurnByDepth) followGap(frame, t, T_robot_optical);
        return;
    }
    // The reference is the one VO started from or the last tracked frame, which VO made its
    // new reference when the camera had moved far enough from the old one.
    if (r.referenceTimestamp == last_tracked_.t) reference_ = last_tracked_;
    if (r.referenceTimestamp != reference_.t) return;  // (cannot happen: VO keeps one reference)
    const auto motion = robotMotion(r, T_robot_optical);
    mrpt::poses::CPose3DPDFGaussian cur = reference_.pdf;
    cur += motion;
    last_step_ = cur.mean - last_tracked_.pdf.mean;  // (both relative to the same node)
    last_step_seconds_ = t - last_tracked_.t;
    if (!chained_.empty()) extendChain(t, motion);
    last_tracked_ = {t, cur};
    last_tracked_features_ = r.frameFeatures;
    trackedFrame(frame, T_robot_optical);
    if (cur.mean.norm() < params_.nodeDistance && rotationAngle(cur.mean) < params_.nodeAngle)
        return;
    // (through the rotation only where the edge keeps VO's correlations of the two: a loose
    // rise correlated with a turn would otherwise turn the step as it is held)
    auto edge = heightHeld(cur, params_.stepHeightSigma, params_.edgeCrossCovariance);
    if (params_.stepMotionPrior && t > node_time_) edge = motionHeld(edge, t - node_time_);
    registerAt(*scan, t, r.frameFeatures, edge, false);
    // Seen from the new node, the reference lies where VO measured it - the motion inverted,
    // with the motion's own covariance (not the node's: that is the edge's).
    mrpt::poses::CPose3DPDFGaussian back;
    motion.inverse(back);
    reference_.pdf = back;
    last_tracked_.pdf = here;
}

void VisualOdometryNRD::dropGyroBefore(double t) {
    // Keep what the next frame's rotation needs: from VO's reference (or this frame) on,
    // and from the last tracked frame (a bridge across a gap, this frame's restart
    // included), for as long as a gap may be bridged.
    const auto since = vo_.referenceTimestamp();
    double keep = since ? std::min(*since, t) : t;
    if (std::isfinite(last_tracked_.t) && t - last_tracked_.t <= params_.gyroBridgeMaxSeconds)
        keep = std::min(keep, last_tracked_.t);
    if (params_.useGravity) {  // (and the window before this frame, for its up)
        keep = std::min(keep, t - params_.gravity.windowSeconds - 0.1);
        gravity_.dropBefore(t - params_.gravityVelocitySeconds);
    }
    gyro_.dropBefore(keep);
}

void VisualOdometryNRD::restartAt(const mrpt::obs::CObservation3DRangeScan& scan, double t,
                                  const vision::VoResult& r, const vision::RgbdFrame& frame,
                                  const Eigen::Isometry3d& T_robot_optical) {
    const mrpt::poses::CPose3DPDFGaussian here;  // a frame at the new node: identity, certain
    // VO (re)starts on this frame: the root, or after a loss a new segment.
    const bool first = m_prev_registered_nodeID == mrpt::graphs::INVALID_NODEID;
    const double gap = first ? 0.0 : t - last_tracked_.t;
    if (!first) {
        ++gaps_;
        gap_seconds_.push_back(gap);
    }
    std::optional<mrpt::poses::CPose3DPDFGaussian> found, byGyro, expected;
    bool byDepthTurn = false;
    if (!first && (params_.useGyro || params_.bridgeTurnByDepth) &&
        gap <= params_.gyroBridgeMaxSeconds) {
        followGap(frame, t, T_robot_optical);
        if (params_.useGyro) byGyro = bridgeByGyro(t);
        if (!byGyro && params_.bridgeTurnByDepth) {
            byGyro = bridgeByDepthTurn(t);
            byDepthTurn = byGyro.has_value();
        }
    }
    // Where the carrier can have gone meanwhile, as far as a motion model knows: what a
    // view found again must agree with (features along one edge - a door frame, a corner -
    // align at any turn about it).
    if (byGyro)
        expected = byGyro;
    else if (!first && last_step_seconds_ > 0)
        expected = bridge(gap);
    if (!first && r.frameFeatures)
        found = relocalize(*r.frameFeatures, T_robot_optical, expected ? &*expected : nullptr);
    if (!first) carryAcrossGap(t);  // (before this frame becomes the last tracked one)
    if (found) {
        // The view came back: the graph goes on from where it was seen before.
        ++relocalized_;
        registerAt(scan, t, r.frameFeatures, *found, false);
    } else if (byGyro) {
        // The gyro (or the depth) saw every turn of the gap: the segment goes on, loose
        // where it must.
        if (byDepthTurn) {
            ++bridged_by_depth_turn_;
        } else {
            ++bridged_by_gyro_;
            if (depth_bridge_.active() && depth_bridge_.aligned() > 0) ++bridged_by_depth_;
        }
        registerAt(scan, t, r.frameFeatures, *byGyro, false);
    } else if (!first && gap <= params_.bridgeMaxSeconds && last_step_seconds_ > 0) {
        // A short gap: where the last velocity carries the camera, as sure as a
        // constant-velocity model is over that long.
        ++bridged_;
        registerAt(scan, t, r.frameFeatures, bridge(gap), false);
    } else {
        if (!first) unbridged_gap_seconds_.push_back(gap);
        registerAt(scan, t, r.frameFeatures, here, !first);
    }
    reference_ = {t, here};
    last_tracked_ = {t, here};
    last_tracked_features_ = r.frameFeatures;
    trackedFrame(frame, T_robot_optical);
    chained_.clear();  // (VO starts again: its velocity is unknown until it has tracked)
    chained_.emplace_back(t, mrpt::poses::CPose3D());
    chained_covariance_.assign(1, Eigen::Matrix3d::Zero());
    chained_rotation_covariance_.assign(1, Eigen::Matrix3d::Zero());
}

void VisualOdometryNRD::extendChain(double t, const mrpt::poses::CPose3DPDFGaussian& motion) {
    chained_.emplace_back(t, chained_.back().second + last_step_);
    // VO's own uncertainty of this frame against its reference, in the chain's axes (turned
    // by this frame's rotation: the reference's differs by a keyframe's turn at most).
    const Eigen::Matrix3d R = chained_.back().second.getRotationMatrix().asEigen();
    const Eigen::Matrix3d C = motion.cov.asEigen().topLeftCorner<3, 3>();
    chained_covariance_.push_back(R * C * R.transpose());
    // (its rotation block: MRPT's yaw, pitch, roll are w_z, w_y, w_x to first order)
    Eigen::Matrix3d Cr;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) Cr(i, j) = motion.cov(5 - i, 5 - j);
    chained_rotation_covariance_.push_back(R * Cr * R.transpose());
    // (the carrier's pace against its turn rate, VO's over the last frames)
    cruise_.add(Eigen::Vector3d(last_step_.x(), last_step_.y(), last_step_.z()), last_step_seconds_,
                turnRateAtLastTracked().mean.norm());
    // (kept: VO's velocity before a gap; with the accelerometer, the window before a node)
    double old = t - std::max(2 * params_.gravityVelocitySeconds,
                              params_.bridgeVelocity.correlationSeconds);
    if (params_.useGravity) old -= params_.gravity.windowSeconds;
    while (chained_.size() > 1 && chained_[1].first < old) {
        chained_.pop_front();
        chained_covariance_.pop_front();
        chained_rotation_covariance_.pop_front();
    }
}

void VisualOdometryNRD::learnGyroBias(const vision::VoResult& r, double t,
                                      const Eigen::Isometry3d& T_robot_optical) {
    const auto g = gyro_.between(r.referenceTimestamp, t);
    if (!g) return;
    // VO's rotation in the gyro's body frame: C R C^T, C the optical frame's rotation in it.
    const Eigen::Matrix3d C = gyro_.sensorOnRobot().linear().transpose() * T_robot_optical.linear();
    // (the camera's own rotation, not the one the gyro joined)
    const Eigen::Matrix3d measured = C * r.T_ref_cur_camera.linear() * C.transpose();
    const double sigma = std::sqrt(r.covariance_camera.topLeftCorner<3, 3>().trace() / 3);
    if (gyro_bias_.update(g->R, measured, sigma, t - r.referenceTimestamp))
        gyro_.setBias(gyro_bias_.bias(), gyro_bias_.sigma());
}

mrpt::poses::CPose3DPDFGaussian VisualOdometryNRD::relativeToLastNode(TNodeID from) const {
    mrpt::poses::CPose3DPDFGaussian chain;  // last node <- from, along the segment's edges
    for (TNodeID id = from; id < m_prev_registered_nodeID; ++id) {
        const Constraint& c = m_graph->edges.find({id, id + 1})->second;
        chain += mrpt::poses::CPose3DPDFGaussian(c.mean, c.cov_inv.inverse_LLt());
    }
    mrpt::poses::CPose3DPDFGaussian back;
    chain.inverse(back);
    return back;
}

std::optional<mrpt::poses::CPose3DPDFGaussian> VisualOdometryNRD::relocalize(
    const vision::FrameFeatures& current, const Eigen::Isometry3d& A,
    const mrpt::poses::CPose3DPDFGaussian* expected) {
    if (params_.relocalizeKeyframes == 0) return std::nullopt;
    // Newest first: the last tracked frame, then the keyframes.
    std::vector<std::pair<mrpt::poses::CPose3DPDFGaussian, const vision::FrameFeatures*>> tries;
    if (last_tracked_features_) tries.emplace_back(last_tracked_.pdf, last_tracked_features_.get());
    for (auto k = recent_keyframes_.rbegin(); k != recent_keyframes_.rend(); ++k) {
        tries.emplace_back(relativeToLastNode(k->first), k->second.get());
    }
    std::uint64_t seed = params_.visual.seed + frames_ * 131;
    for (const auto& [where, features] : tries) {
        const auto a = vo_.align(*features, current, ++seed);
        if (!a.success) continue;
        vision::VoResult motion;
        motion.T_ref_cur = a.estimate.transform;
        motion.covariance = a.estimate.covariance;
        mrpt::poses::CPose3DPDFGaussian edge = where;
        edge += robotMotion(motion, A);
        if (expected && squaredMahalanobis(*expected, edge) > kChi2Se3999) {
            ++relocalizations_rejected_;
            continue;
        }
        return edge;
    }
    return std::nullopt;
}

void VisualOdometryNRD::registerAt(const mrpt::obs::CObservation3DRangeScan& scan, double t,
                                   const std::shared_ptr<const vision::FrameFeatures>& features,
                                   const mrpt::poses::CPose3DPDFGaussian& edge, bool restart) {
    bool keyframe = true;
    TNodeID id = m_graph->root;
    node_time_ = t;
    const double lostAfter = last_tracked_.t;  // (last_tracked_ becomes this frame below)
    if (m_prev_registered_nodeID == mrpt::graphs::INVALID_NODEID) {
        m_graph->nodes[m_graph->root] = mrpt::poses::CPose3D();  // the camera starts the map
        m_prev_registered_nodeID = m_graph->root;
    } else {
        Constraint c = edgeOf(edge, params_.edgeCrossCovariance);
        if (restart) {
            // Across a VO gap: no idea where the camera went.
            c.mean = mrpt::poses::CPose3D();
            c.cov_inv.setZero();
            for (int k = 0; k < 6; ++k)
                c.cov_inv(k, k) = 1 / (params_.lostEdgeSigma * params_.lostEdgeSigma);
            ++segment_;
        }
        m_since_prev_node_PDF = c;
        // MRPT's registerNewNodeAtEnd() places the node at getCurrentRobotPosEstimation(),
        // the last node + last_tracked_: make that the edge's end first (across a gap the last
        // tracked frame is not the new node's frame).
        last_tracked_ = {t, mrpt::poses::CPose3DPDFGaussian(c.mean)};
        registerNewNodeAtEnd();
        id = m_prev_registered_nodeID;
        since_keyframe_ = since_keyframe_ + c.mean;
        keyframe = restart || since_keyframe_.norm() >= params_.keyframeDistance ||
                   rotationAngle(since_keyframe_) >= params_.keyframeAngle;
    }
    if (nodes_) {
        NodeRecord rec;
        rec.timestamp = t;
        rec.segment = segment_;
        rec.keyframe = keyframe;
        rec.attitude = nodeAttitude(id, t, scan);
        if (restart) {
            rec.liftTime = lostAfter;  // tracking lost after this frame ...
            rec.putDownTime = t;       // ... and found again at this one
        }
        if (keyframe) {
            rec.features = features;
            rec.T_robot_camera = odometry::opticalFrameOnRobot(scan.sensorPose);
            if (keep_depth_) rec.depth = makeKeyframeDepth(scan, params_.visual.depthSampling);
            if (params_.mapPixelStep > 0) {
                rec.cloud = std::make_shared<KeyframeCloud>(
                    makeKeyframeCloud(scan, params_.mapPixelStep, params_.mapMaxDepth));
            }
        }
        nodes_->add(id, std::move(rec));
    }
    if (restart) recent_keyframes_.clear();  // (a new segment: nothing before it is related)
    if (keyframe) {
        since_keyframe_ = mrpt::poses::CPose3D();
        ++keyframes_;
        if (features) recent_keyframes_.emplace_back(id, features);
        while (recent_keyframes_.size() > static_cast<std::size_t>(params_.relocalizeKeyframes))
            recent_keyframes_.pop_front();
    }
    just_registered_ = id;
}

bool VisualOdometryNRD::finish() {
    just_registered_.reset();
    return false;  // nodes are placed at frames as they come: nothing waits
}

bool VisualOdometryNRD::checkRegistrationCondition() { return false; }

VisualOdometryNRD::global_pose_t VisualOdometryNRD::getCurrentRobotPosEstimation() const {
    global_pose_t pose;
    if (m_prev_registered_nodeID != mrpt::graphs::INVALID_NODEID)
        pose = m_graph->nodes.at(m_prev_registered_nodeID);
    return global_pose_t(pose + last_tracked_.pdf.mean);
}

std::function<void(const mrpt::obs::CObservation::Ptr&)> VisualOdometryNRD::preparer(std::size_t inFlight) {
    // (the frames in flight, and the one being taken while the reader adds the next)
    prepared_.setCapacity(inFlight + 1);
    return [this](const mrpt::obs::CObservation::Ptr& obs) { prepared_.prepareAhead(obs); };
}

JsonObject VisualOdometryNRD::describe() const {
    JsonObject params;
    params_.describeAll(params);
    JsonObject stats;
    stats.set("rgbd_frames", frames_)
        .set("failed_frames", failed_frames_)
        .set("keyframes", keyframes_)
        .set("vo_gaps", gaps_)
        .set("vo_gap_seconds", gap_seconds_)
        .set("vo_gaps_bridged", bridged_)
        .set("vo_gaps_bridged_by_gyro", bridged_by_gyro_)
        .set("vo_unbridged_gap_seconds", unbridged_gap_seconds_)
        .set("vo_gaps_relocalized", relocalized_)
        .set("vo_relocalizations_against_the_motion_model", relocalizations_rejected_)
        .set("segments", segment_ + 1)
        .set("vo_restarts_carrying_velocity", restarts_carrying_velocity_)
        .set("vo_ms_per_frame", detail::voTimingJson(vo_.totals()))
        .set("frames_prepared_ahead", prepared_.counts().ahead)
        .set("frames_prepared_in_the_loop", prepared_.counts().here);
    if (params_.useGyro) {
        const Eigen::Vector3d b = gyro_bias_.bias() * 180 / M_PI;
        stats.set("frames_with_gyro_rotation", gyro_priors_)
            .set("gyro_bias_deg_per_s", std::vector<double>{b.x(), b.y(), b.z()})
            .set("gyro_bias_sigma_deg_per_s", gyro_bias_.sigma() * 180 / M_PI)
            .set("gyro_bias_updates", gyro_bias_.updates())
            .set("gyro_bias_outliers", gyro_bias_.skipped());
        if (params_.bridgeByDepth) {
            stats.set("vo_gaps_bridged_by_depth", bridged_by_depth_)
                .set("depth_bridge_frames_aligned", depth_bridge_aligned_)
                .set("depth_bridge_frames_rejected", depth_bridge_rejected_);
        }
    }
    if (params_.bridgeTurnByDepth) {
        stats.set("vo_gaps_bridged_by_depth_turn", bridged_by_depth_turn_);
        if (!params_.useGyro) {
            stats.set("depth_bridge_frames_aligned", depth_bridge_aligned_)
                .set("depth_bridge_frames_rejected", depth_bridge_rejected_);
        }
    }
    if (params_.bridgeByDepth && params_.bridgeCruiseSeconds > 0) {
        stats.set("depth_bridge_steps_cruising", depth_bridge_cruising_)
            .set("depth_bridge_steps_turning_beyond_cruise", depth_bridge_beyond_cruise_);
    }
    if (params_.useGravity) stats.set("nodes_with_measured_up", attitude_priors_);
    if (params_.carrierTiltSigma > 0) stats.set("nodes_with_carrier_up", carrier_ups_);
    if (params_.floorLevel) {
        stats.set("nodes_with_floor_up", floor_.ups())
            .set("nodes_with_floor_height", floor_.heights())
            .set("level_surfaces_beyond_the_up_gate", floor_.rejected());
        if (params_.useGravity)
            stats.set("nodes_whose_floor_and_accelerometer_disagreed", floor_disagreed_);
    }
    JsonObject why;
    for (const auto& [reason, count] : failures_) why.set(reason, count);
    stats.set("failed_frames_by_reason", why);
    return JsonObject().set("class", getClassName()).set("params", params).set("stats", stats);
}

}  // namespace lodestone::graphslam
