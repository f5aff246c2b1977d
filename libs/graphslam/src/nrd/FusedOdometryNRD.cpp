#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/nrd/FusedOdometryNRD.h>

#include "VoTimingJson.h"
#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/obs/CObservationWheelDrop.h>
#include <lodestone/odometry/RgbdObservationFrame.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lodestone::graphslam {

FusedOdometryNRD::FusedOdometryNRD() {
    setClassName("FusedOdometryNRD");
    odometry_ = std::make_unique<odometry::FusedOdometry>(params_.odometry);
}

void FusedOdometryNRD::configure(const mrpt::config::CConfigFileBase& ini) {
    Params p = params_;  // all or nothing: a failed read leaves the decider as it was
    p.odometry.loadFromConfigFile(ini, "odometry_fusion");
    config::IniSection s(ini, "FusedOdometryNRD", config::sourceName(ini));
    p.read(s);  // NodeSpacing: node and keyframe intervals, map clouds
    p.kidnapEdgeSigma = s.getDouble("kidnap_edge_sigma", p.kidnapEdgeSigma);
    p.useWheelDrop = s.getBool("kidnap_wheel_drop", p.useWheelDrop);
    p.detection = kidnap::KidnapDetector::readParams(ini);
    if (!(p.kidnapEdgeSigma > 0)) s.fail("kidnap_edge_sigma", "must be > 0");
    s.finish();
    params_ = p;
    odometry_ = std::make_unique<odometry::FusedOdometry>(params_.odometry);
    detector_.reset();
    if (params_.detection.motion || params_.detection.magnetic)
        detector_ = std::make_unique<kidnap::KidnapDetector>(params_.detection);
}

std::set<std::string> FusedOdometryNRD::requiredObservations() const {
    // Encoder ticks with RGB-D frames (frames give the node times, encoder samples resolve
    // them), or pose-only odometry on its own (FusedOdometry); the latter needs no frames.
    return {"CObservationOdometry"};
}

bool FusedOdometryNRD::updateState(mrpt::obs::CActionCollection::Ptr /*action*/,
                                   mrpt::obs::CSensoryFrame::Ptr observations,
                                   mrpt::obs::CObservation::Ptr observation) {
    just_registered_.reset();
    if (observation) consume(observation);
    if (observations) {
        for (const auto& o : *observations) consume(o);
    }
    return registerPending();
}

bool FusedOdometryNRD::finish() {
    just_registered_.reset();
    for (auto& e : odometry_->flush()) {
        if (detector_) onDetectorEvent(detector_->onFrame(e));
        held_.push_back(std::move(e));
    }
    release(INFINITY);
    return registerPending();
}

void FusedOdometryNRD::onDetectorEvent(const std::optional<kidnap::KidnapDetector::Event>& ev) {
    if (ev) onWheelDrop(ev->lifted, ev->time);
}

void FusedOdometryNRD::release(double now) {
    const double latency = detector_ ? params_.detection.latency : 0.0;
    while (!held_.empty() && held_.front().timestamp <= now - latency) {
        const auto e = std::move(held_.front());
        held_.pop_front();
        take(e);
        // Frames up to this one are resolved: a node can no longer be placed at an older one.
        while (!recent_frames_.empty() &&
               mrpt::Clock::toDouble(recent_frames_.front()->timestamp) < e.timestamp) {
            recent_frames_.pop_front();
        }
        while (!recent_features_.empty() && recent_features_.begin()->first < e.timestamp) {
            recent_features_.erase(recent_features_.begin());
        }
    }
}

void FusedOdometryNRD::consume(const mrpt::obs::CObservation::Ptr& obs) {
    const double now = mrpt::Clock::toDouble(obs->timestamp);
    if (auto drop = std::dynamic_pointer_cast<obs::CObservationWheelDrop>(obs)) {
        if (params_.useWheelDrop) onWheelDrop(drop->lifted(), now);
        return;
    }
    if (auto mag = std::dynamic_pointer_cast<obs::CObservationMagnetometer>(obs)) {
        magnetic_.push_back({now, mag->sensorLabel, mag->field, mag->sensorPose});
        if (detector_) {
            if (detector_sensor_.empty()) detector_sensor_ = mag->sensorLabel;
            if (mag->sensorLabel == detector_sensor_) {
                const double norm = std::sqrt(mag->field.x * mag->field.x +
                                              mag->field.y * mag->field.y +
                                              mag->field.z * mag->field.z);
                onDetectorEvent(detector_->onMagnetic(now, norm));
            }
        }
        release(now);
        return;
    }
    if (auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs)) {
        ++frames_;
        recent_frames_.push_back(scan);
    }
    for (auto& e : odometry_->process(obs)) {
        if (e.visual.frameFeatures) recent_features_[e.timestamp] = e.visual.frameFeatures;
        if (detector_) onDetectorEvent(detector_->onFrame(e));
        held_.push_back(std::move(e));
    }
    release(now);
}

void FusedOdometryNRD::onWheelDrop(bool lifted, double t) {
    // Frames are resolved a little after they are taken (FusedOdometry waits for the next
    // encoder sample), so the kidnap is an interval of frame times, not a state.
    if (lifted && !lifted_) {
        lifted_ = true;
        lift_time_ = t;
        down_time_.reset();
        ++kidnaps_;
    } else if (!lifted && lifted_) {
        lifted_ = false;
        down_time_ = t;
    }
}

void FusedOdometryNRD::take(const odometry::FusedOdometry::Estimate& e) {
    const bool afterLift = lift_time_ && e.timestamp >= *lift_time_;
    const bool beforeDown = !down_time_ || e.timestamp < *down_time_;
    if (afterLift && beforeDown) {
        // Carried: what odometry sees is not the robot driving. Close the segment where the
        // robot was lifted, once.
        ++frames_lifted_;
        const auto& m = since_node_.mean;
        if (!segment_closed_ && have_estimate_ && (m.x() != 0 || m.y() != 0 || m.phi() != 0)) {
            close_segment_ = true;
        }
        segment_closed_ = true;
        return;
    }
    if (afterLift && down_time_) {
        // The first frame after the put-down starts a new segment; its own increment spans
        // the carry and is dropped, as are the magnetometer readings of the carry.
        magnetic_.erase(std::remove_if(magnetic_.begin(), magnetic_.end(),
                                       [&](const MagneticSample& m) {
                                           return m.timestamp >= *lift_time_ &&
                                                  m.timestamp < *down_time_;
                                       }),
                        magnetic_.end());
        restart_lift_ = *lift_time_;
        restart_down_ = *down_time_;
        lift_time_.reset();
        down_time_.reset();
        segment_closed_ = false;
        restart_ = true;
        since_node_ = mrpt::poses::CPosePDFGaussian();
        since_node_scale_.setZero();
        last_time_ = e.timestamp;
        return;
    }
    const bool first = !have_estimate_;
    have_estimate_ = true;
    last_time_ = e.timestamp;
    if (first && after_map_) {
        // Somewhere in the loaded map: the first node starts a segment of its own, tied to the
        // map as across a kidnap (no lift or put-down time: the run began there).
        restart_ = true;
        restart_lift_ = restart_down_ = NAN;
        since_node_ = mrpt::poses::CPosePDFGaussian();
        since_node_scale_.setZero();
        return;
    }
    if (first) {
        // The root: node 0 at the origin, where the odometry starts.
        m_graph->nodes[m_graph->root] = mrpt::poses::CPose3D();
        m_prev_registered_nodeID = m_graph->root;
        if (nodes_) nodes_->add(m_graph->root, recordFor(e.timestamp, true));
        ++keyframes_;
        just_registered_ = m_graph->root;
        return;
    }
    since_node_scale_ = odometry::DiffDriveOdometry::composeScaleJacobian(
        since_node_.mean, since_node_scale_, e.increments.front().mean, e.wheelScale.front());
    since_node_ += e.increments.front();
    since_keyframe_ = since_keyframe_ + e.increments.front().mean;
}

bool FusedOdometryNRD::checkRegistrationCondition() {
    if (!have_estimate_ || just_registered_) return false;
    if (close_segment_ || restart_) return true;
    if (lift_time_) return false;  // carried, or waiting for the first frame after it
    const auto& m = since_node_.mean;
    return std::hypot(m.x(), m.y()) >= params_.nodeDistance ||
           std::abs(m.phi()) >= params_.nodeAngle;
}

void FusedOdometryNRD::continueAfterMap(TNodeID lastMapNode, int segment) {
    if (have_estimate_) throw std::logic_error("FusedOdometryNRD: a map is loaded before any data");
    m_prev_registered_nodeID = lastMapNode;
    segment_ = segment - 1;  // (the restart's node counts one up)
    after_map_ = true;
}

FusedOdometryNRD::global_pose_t FusedOdometryNRD::getCurrentRobotPosEstimation() const {
    global_pose_t pose;
    if (m_prev_registered_nodeID != mrpt::graphs::INVALID_NODEID) {
        pose = m_graph->nodes.at(m_prev_registered_nodeID);
    }
    const auto& m = since_node_.mean;
    return global_pose_t(pose + mrpt::poses::CPose3D(m.x(), m.y(), 0, m.phi(), 0, 0));
}

bool FusedOdometryNRD::registerPending() {
    if (!checkRegistrationCondition()) return just_registered_.has_value();
    Constraint c = planarConstraint(since_node_);
    close_segment_ = false;
    const bool keyframe = restart_ ||
                          std::hypot(since_keyframe_.x(), since_keyframe_.y()) >=
                              params_.keyframeDistance ||
                          std::abs(since_keyframe_.phi()) >= params_.keyframeAngle;
    const bool restart = restart_;
    if (restart_) {
        // Across a kidnap: no idea where the robot went.
        const double w = 1 / (params_.kidnapEdgeSigma * params_.kidnapEdgeSigma);
        for (int k : {0, 1, 3}) c.cov_inv(k, k) = w;
        c.cov_inv(0, 1) = c.cov_inv(1, 0) = c.cov_inv(0, 3) = c.cov_inv(3, 0) = 0;
        c.cov_inv(1, 3) = c.cov_inv(3, 1) = 0;
        ++segment_;
        restart_ = false;
    }
    m_since_prev_node_PDF = c;
    registerNewNodeAtEnd();  // MRPT's: node at previous + m_since_prev_node_PDF, edge c
    const TNodeID id = m_prev_registered_nodeID;
    if (nodes_) {
        NodeRecord rec = recordFor(last_time_, keyframe);
        if (restart) {
            rec.liftTime = restart_lift_;
            rec.putDownTime = restart_down_;
        } else if (!since_node_scale_.isZero()) {  // (none where no wheel moved it)
            rec.wheelScale = since_node_scale_;
        }
        nodes_->add(id, std::move(rec));
    }
    if (keyframe) {
        since_keyframe_ = mrpt::poses::CPose2D();
        ++keyframes_;
    }
    since_node_ = mrpt::poses::CPosePDFGaussian();
    since_node_scale_.setZero();
    just_registered_ = id;
    return true;
}

NodeRecord FusedOdometryNRD::recordFor(double timestamp, bool keyframe) {
    NodeRecord r;
    r.timestamp = timestamp;
    r.segment = segment_;
    r.keyframe = keyframe;
    // Readings up to the node's time are its own; those taken while carried belong to nobody.
    while (!magnetic_.empty() && magnetic_.front().timestamp <= timestamp) {
        const auto& m = magnetic_.front();
        const bool carried = lift_time_ && m.timestamp >= *lift_time_;
        if (!carried) r.magnetic.push_back(m);
        magnetic_.pop_front();
    }
    if (!keyframe) return r;
    const auto f = recent_features_.find(timestamp);
    if (f != recent_features_.end()) r.features = f->second;
    for (const auto& frame : recent_frames_) {
        if (std::abs(mrpt::Clock::toDouble(frame->timestamp) - timestamp) > 1e-6) continue;
        r.T_robot_camera = odometry::opticalFrameOnRobot(frame->sensorPose);
        if (keep_depth_) r.depth = makeKeyframeDepth(*frame, params_.odometry.visual.depthSampling);
        if (params_.mapPixelStep > 0) {
            r.cloud = std::make_shared<KeyframeCloud>(
                makeKeyframeCloud(*frame, params_.mapPixelStep, params_.mapMaxDepth));
        }
        break;
    }
    return r;
}

std::function<void(const mrpt::obs::CObservation::Ptr&)> FusedOdometryNRD::preparer(std::size_t inFlight) {
    // (the frames in flight, and the one being taken while the reader adds the next)
    odometry_->preparedFrames().setCapacity(inFlight + 1);
    return [this](const mrpt::obs::CObservation::Ptr& obs) {
        odometry_->preparedFrames().prepareAhead(obs);
    };
}

std::string FusedOdometryNRD::trackingState() const {
    if (lifted_) return "kidnapped (carried)";
    std::string state = frames_ == 0 ? "wheels" : "wheels + camera";
    if (segment_ > 0) state += ", segment " + std::to_string(segment_);
    return state;
}

JsonObject FusedOdometryNRD::describe() const {
    JsonObject params;
    params_.describe(params);
    params.set("kidnap_edge_sigma", params_.kidnapEdgeSigma)
        .set("kidnap_wheel_drop", params_.useWheelDrop)
        .set("kidnap_detection_motion", params_.detection.motion)
        .set("kidnap_detection_magnetic", params_.detection.magnetic)
        .set("odometry_method", params_.odometry.method)
        .set("wheel_base", params_.odometry.wheels.wheelBase)
        .set("wheel_radius", params_.odometry.wheels.wheelRadius)
        .set("ticks_per_rev", params_.odometry.wheels.ticksPerRev);
    JsonObject stats;
    stats.set("rgbd_frames", frames_)
        .set("frames_while_lifted", frames_lifted_)
        .set("kidnaps", kidnaps_)
        .set("keyframes", keyframes_)
        .set("segments", segment_ + 1)
        .set("vo_ms_per_frame", detail::voTimingJson(odometry_->visual().totals()))
        .set("frames_prepared_ahead", odometry_->preparedFrames().counts().ahead)
        .set("frames_prepared_in_the_loop", odometry_->preparedFrames().counts().here)
        .set("vo_guided_frames", odometry_->visual().totals().guided)
        .set("vo_guided_fallbacks", odometry_->visual().totals().guidedFallback)
        .set("vo_guided_pairs_compared",
             odometry_->visual().totals().guidedPairsAll > 0
                 ? odometry_->visual().totals().guidedPairsCompared /
                       odometry_->visual().totals().guidedPairsAll
                 : 0.0);
    if (detector_) {
        const auto& d = detector_->stats();
        stats.set("detected_lifts", d.lifts)
            .set("detected_by_motion", d.byMotion)
            .set("detected_by_rise", d.byRise)
            .set("detected_by_magnetic", d.byMagnetic)
            .set("detected_put_downs", d.putDowns);
    }
    return JsonObject().set("class", getClassName()).set("params", params).set("stats", stats);
}

}  // namespace lodestone::graphslam
