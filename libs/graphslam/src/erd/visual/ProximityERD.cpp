#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/Se3Pose.h>
#include <lodestone/graphslam/erd/visual/ProximityERD.h>
#include <lodestone/vision/KeyframePair.h>

#include <algorithm>
#include <cmath>

#include "../../Stopwatch.h"

namespace lodestone::graphslam {

ProximityERD::Params::Params() {
    // As SubmapMatcher's node-to-node phase: optical frames, as visual odometry aligns them.
    matcher.ratio = 0.8;
    matcher.crossCheck = false;
    ransac.iterations = 300;
    ransac.confidence = 0.999;
    ransac.minInliers = 20;
    ransac.minInlierRatio = 0.25;
}

ProximityERD::ProximityERD() : matcher_(params_.matcher), ransac_(params_.ransac) {
    setClassName("ProximityERD");
}

void ProximityERD::configure(const mrpt::config::CConfigFileBase& ini) {
    config::IniSection s(ini, "ProximityERD", config::sourceName(ini));
    Params p = params_;  // all or nothing
    p.radius = s.getDouble("radius", p.radius);
    p.maxViewAngleDeg = s.getDouble("max_view_angle_deg", p.maxViewAngleDeg);
    p.maxTravel = s.getDouble("max_travel", p.maxTravel);
    p.maxCandidates = static_cast<std::size_t>(
        s.getInt("max_candidates", static_cast<int>(p.maxCandidates)));
    p.matcher.read(s);
    p.ransac.read(s);
    p.depth = s.getBool("depth", p.depth);
    p.onlyInformative = s.getBool("only_informative", p.onlyInformative);
    p.gateChi2 = s.getDouble("gate_chi2", p.gateChi2);
    p.minSigmaXY = s.getDouble("min_sigma_xy", p.minSigmaXY);
    p.minSigmaYaw = s.getDouble("min_sigma_yaw_deg", p.minSigmaYaw * 180 / M_PI) * M_PI / 180;
    if (!(p.radius > 0)) s.fail("radius", "must be > 0");
    if (!(p.maxViewAngleDeg > 0 && p.maxViewAngleDeg <= 180))
        s.fail("max_view_angle_deg", "must be in (0, 180]");
    if (!(p.maxTravel > 0)) s.fail("max_travel", "must be > 0");
    if (p.maxCandidates < 1) s.fail("max_candidates", "must be >= 1");
    if (!(p.gateChi2 > 0)) s.fail("gate_chi2", "must be > 0");
    if (!(p.minSigmaXY > 0) || !(p.minSigmaYaw > 0)) s.fail("min_sigma_xy", "floors must be > 0");
    s.finish();
    params_ = p;
    matcher_ = vision::DescriptorMatcher(params_.matcher);
    ransac_ = vision::RigidRansac(params_.ransac);
}

bool ProximityERD::updateState(mrpt::obs::CActionCollection::Ptr, mrpt::obs::CSensoryFrame::Ptr,
                               mrpt::obs::CObservation::Ptr) {
    const std::size_t before = stats_.accepted;
    for (; seen_ < m_graph->nodes.size() && nodes_ && nodes_->has(seen_); ++seen_) onNode(seen_);
    return stats_.accepted > before;
}

Eigen::Isometry3d ProximityERD::poseOf(TNodeID id) const {
    return isometryOf(m_graph->nodes.at(id));
}

void ProximityERD::onNode(TNodeID id) {
    // Travel and the odometry's variance along the chain, from the edge that brought the node.
    const OdometryStep step = odometryStepInto(*m_graph, id);
    travel_.push_back(travel_.empty() ? 0.0 : travel_.back() + step.length);
    chain_xy_.push_back((chain_xy_.empty() ? 0.0 : chain_xy_.back()) + 0.5 * step.varianceXY);
    chain_yaw_.push_back((chain_yaw_.empty() ? 0.0 : chain_yaw_.back()) + step.varianceYaw);
    const NodeRecord& rec = nodes_->at(id);
    if (rec.depth) {
        if (rec.keyframe && rec.features && params_.depth) depth_[id] = rec.depth;
        nodes_->releaseDepth(id);
    }
    // (the window's older clouds: no later keyframe reaches them)
    while (!depth_.empty() && travel_[id] - travel_[depth_.begin()->first] > params_.maxTravel)
        depth_.erase(depth_.begin());
    if (!rec.keyframe || !rec.features) return;
    ++stats_.keyframes;
    if (id >= map_nodes_) {
        for (const TNodeID from : candidates(id)) tryPair(from, id);
    }
    keyframes_.push_back(id);
}

std::vector<TNodeID> ProximityERD::candidates(TNodeID id) const {
    const NodeRecord& rec = nodes_->at(id);
    const Eigen::Isometry3d camera = poseOf(id) * rec.T_robot_camera;
    const double cosMax = std::cos(params_.maxViewAngleDeg * M_PI / 180);
    std::vector<TNodeID> out;
    // Newest first, so the scan stops at max_travel; the keyframe before is VO's reference.
    for (std::size_t k = keyframes_.size(); k-- > 0;) {
        const TNodeID j = keyframes_[k];
        if (k + 1 == keyframes_.size()) continue;
        if (travel_[id] - travel_[j] > params_.maxTravel) break;
        const NodeRecord& other = nodes_->at(j);
        if (other.segment != rec.segment || j < map_nodes_) continue;
        const Eigen::Isometry3d c = poseOf(j) * other.T_robot_camera;
        if ((c.translation() - camera.translation()).norm() > params_.radius) continue;
        if (c.linear().col(2).dot(camera.linear().col(2)) < cosMax) continue;
        out.push_back(j);
    }
    // The furthest back first: they hold the most of the odometry's drift.
    std::reverse(out.begin(), out.end());
    if (out.size() > params_.maxCandidates) out.resize(params_.maxCandidates);
    return out;
}

void ProximityERD::tryPair(TNodeID from, TNodeID to) {
    ++stats_.candidates;
    const auto t0 = Clock::now();
    const NodeRecord& a = nodes_->at(from);
    const NodeRecord& b = nodes_->at(to);
    auto al = vision::alignKeyframePair(matcher_, ransac_, *a.features, a.T_robot_camera,
                                        *b.features, b.T_robot_camera,
                                        (std::uint64_t(to) << 20) ^ std::uint64_t(from));
    Record r;
    r.from = from;
    r.to = to;
    r.matches = al.matches;
    r.inliers = al.inliers;
    r.aligned = al.success;
    if (!al.success) {
        stats_.alignMs += msSince(t0);
        records_.push_back(r);
        return;
    }
    ++stats_.aligned;
    const auto da = depth_.find(from), db = depth_.find(to);
    if (da != depth_.end() && db != depth_.end()) {
        vision::joinKeyframeDepth(vision::PointToPlaneIcp(params_.icp), *da->second,
                                  a.T_robot_camera, *db->second, b.T_robot_camera, al);
        stats_.depthJoined += al.depthJoined;
        stats_.depthDisagreed += al.depthDisagreed;
        r.depthJoined = al.depthJoined;
        r.depthDisagreed = al.depthDisagreed;
    }
    stats_.alignMs += msSince(t0);
    if (params_.depth && (!al.depthJoined || al.depthDisagreed)) {
        // (features and depth that disagree beyond their covariances: one of them is wrong -
        // a link is not needed to hold the chain together, so none is made)
        ++stats_.depthFailed;
        records_.push_back(r);
        return;
    }
    r.relative = al.referenceToQuery;
    // Against the graph's relative pose: the odometry's variance along the chain between the
    // two nodes (a node's interval only where it moved) plus the alignment's own, floored.
    const Eigen::Isometry3d graph = poseOf(from).inverse() * poseOf(to);
    const Eigen::Isometry3d diff = graph.inverse() * al.referenceToQuery;
    const double dyaw = std::atan2(diff.linear()(1, 0), diff.linear()(0, 0));
    const double chainXY = chain_xy_[to] - chain_xy_[from], chainYaw = chain_yaw_[to] - chain_yaw_[from];
    const double linkXY = 0.5 * (al.covariance(3, 3) + al.covariance(4, 4)) +
                          params_.minSigmaXY * params_.minSigmaXY;
    const double linkYaw = al.covariance(2, 2) + params_.minSigmaYaw * params_.minSigmaYaw;
    if (params_.onlyInformative && linkXY >= chainXY && linkYaw >= chainYaw) {
        ++stats_.uninformative;
        records_.push_back(r);
        return;
    }
    r.gate2 = diff.translation().head<2>().squaredNorm() / (chainXY + linkXY) +
              dyaw * dyaw / (chainYaw + linkYaw);
    if (!(r.gate2 <= params_.gateChi2)) {
        ++stats_.refusedByGate;
        records_.push_back(r);
        return;
    }
    r.accepted = true;
    ++stats_.accepted;
    registerClosure(
        from, to,
        closureConstraint(al.referenceToQuery, al.covariance, params_.minSigmaXY, params_.minSigmaYaw),
        records_.size(), false, static_cast<double>(al.inliers));
    records_.push_back(r);
}

JsonObject ProximityERD::describe() const {
    JsonObject params;
    params.set("radius", params_.radius)
        .set("max_view_angle_deg", params_.maxViewAngleDeg)
        .set("max_travel", params_.maxTravel)
        .set("max_candidates", params_.maxCandidates)
        .set("min_inliers", params_.ransac.minInliers)
        .set("depth", params_.depth)
        .set("only_informative", params_.onlyInformative)
        .set("gate_chi2", params_.gateChi2);
    JsonObject stats;
    stats.set("keyframes", stats_.keyframes)
        .set("candidates", stats_.candidates)
        .set("aligned", stats_.aligned)
        .set("depth_failed", stats_.depthFailed)
        .set("uninformative", stats_.uninformative)
        .set("refused_by_gate", stats_.refusedByGate)
        .set("accepted", stats_.accepted)
        .set("depth_joined", stats_.depthJoined)
        .set("depth_disagreed", stats_.depthDisagreed)
        .set("align_ms_total", stats_.alignMs);
    return JsonObject().set("class", getClassName()).set("params", params).set("stats", stats);
}

}  // namespace lodestone::graphslam
