#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/erd/visual/OrbSubmapERD.h>
#include <lodestone/graphslam/Se3Pose.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "../../Stopwatch.h"

namespace lodestone::graphslam {

OrbSubmapERD::OrbSubmapERD() {
    setClassName("OrbSubmapERD");
    matcher_ = std::make_unique<vision::SubmapMatcher>(params_.matcher);
    catalog_ = std::make_unique<vision::SubmapCatalog>();
}

void OrbSubmapERD::configure(const mrpt::config::CConfigFileBase& ini) {
    config::IniSection s(ini, "OrbSubmapERD", config::sourceName(ini));
    Params p = params_;  // all or nothing
    p.submapMaxKeyframes = s.getInt("submap_max_keyframes", p.submapMaxKeyframes);
    p.submapMaxLength = s.getDouble("submap_max_length", p.submapMaxLength);
    p.submapMaxSigma = s.getDouble("submap_max_sigma", p.submapMaxSigma);
    p.submapMaxFeatures = static_cast<std::size_t>(
        s.getInt("submap_max_features", static_cast<int>(p.submapMaxFeatures)));
    p.submap.mergeRadius = s.getDouble("merge_radius", p.submap.mergeRadius);
    p.submap.mergeMaxDistance = s.getInt("merge_max_distance", p.submap.mergeMaxDistance);
    p.minTravelGap = s.getDouble("min_travel_gap", p.minTravelGap);
    p.searchRadius = s.getDouble("search_radius", p.searchRadius);
    p.driftPerMetre = s.getDouble("drift_per_metre", p.driftPerMetre);
    p.nearCandidates =
        static_cast<std::size_t>(s.getInt("near_candidates", static_cast<int>(p.nearCandidates)));
    p.similarCandidates = static_cast<std::size_t>(
        s.getInt("similar_candidates", static_cast<int>(p.similarCandidates)));
    p.minVotes = s.getInt("min_votes", p.minVotes);
    auto& m = p.matcher;
    m.matcher.maxDistance = s.getInt("match_max_distance", m.matcher.maxDistance);
    m.matcher.ratio = s.getDouble("match_ratio", m.matcher.ratio);
    m.phase1MaxFeatures = static_cast<std::size_t>(
        s.getInt("phase1_max_features", static_cast<int>(m.phase1MaxFeatures)));
    m.phase1.threshold = s.getDouble("phase1_threshold", m.phase1.threshold);
    m.phase1.minInliers = s.getInt("phase1_min_inliers", m.phase1.minInliers);
    m.phase1.minInlierRatio = s.getDouble("phase1_min_inlier_ratio", m.phase1.minInlierRatio);
    m.phase2.minInliers = s.getInt("phase2_min_inliers", m.phase2.minInliers);
    m.phase2.minInlierRatio = s.getDouble("phase2_min_inlier_ratio", m.phase2.minInlierRatio);
    m.phase1Fallback = s.getBool("phase1_fallback", m.phase1Fallback);
    m.fallbackMinInliers = static_cast<std::size_t>(
        s.getInt("phase1_fallback_min_inliers", static_cast<int>(m.fallbackMinInliers)));
    p.strongInliers = s.getInt("relocation_strong_inliers", p.strongInliers);
    if (p.strongInliers < 0) s.fail("relocation_strong_inliers", "must be >= 0");
    p.minSigmaXY = s.getDouble("min_sigma_xy", p.minSigmaXY);
    p.minSigmaYaw = s.getDouble("min_sigma_yaw_deg", p.minSigmaYaw * 180 / M_PI) * M_PI / 180;
    if (p.submapMaxKeyframes < 1) s.fail("submap_max_keyframes", "must be >= 1");
    if (!(p.submapMaxSigma > 0)) s.fail("submap_max_sigma", "must be > 0");
    if (p.minTravelGap < 0) s.fail("min_travel_gap", "must be >= 0");
    if (m.phase1.minInliers < 3) s.fail("phase1_min_inliers", "must be >= 3");
    if (m.phase2.minInliers < 3) s.fail("phase2_min_inliers", "must be >= 3");
    if (!(p.minSigmaXY > 0) || !(p.minSigmaYaw > 0)) s.fail("min_sigma_xy", "floors must be > 0");
    s.finish();
    params_ = p;
    matcher_ = std::make_unique<vision::SubmapMatcher>(params_.matcher);
}

bool OrbSubmapERD::updateState(mrpt::obs::CActionCollection::Ptr, mrpt::obs::CSensoryFrame::Ptr,
                               mrpt::obs::CObservation::Ptr) {
    const std::size_t before = stats_.accepted;
    for (; seen_ < m_graph->nodes.size() && nodes_ && nodes_->has(seen_); ++seen_) onNode(seen_);
    return stats_.accepted > before;
}

Eigen::Isometry3d OrbSubmapERD::poseOf(TNodeID id) const {
    return isometryOf(m_graph->nodes.at(id));
}

void OrbSubmapERD::onNode(TNodeID id) {
    // Distance travelled and odometry uncertainty, from the edge that brought the node.
    const OdometryStep odometry = odometryStepInto(*m_graph, id);
    const double step = odometry.length, variance = odometry.varianceXY;
    travel_.push_back(travel_.empty() ? 0.0 : travel_.back() + step);
    if (++nodes_since_refresh_ >= 25) refreshCentres();
    if (open_) {
        open_variance_ += variance;
        // A kidnap edge (or any very uncertain step) ends the submap: its frame would lie.
        const bool tooUncertain = std::sqrt(open_variance_) > params_.submapMaxSigma;
        const bool tooLong = travel_.back() - open_travel_start_ > params_.submapMaxLength;
        if (tooUncertain || tooLong) closeOpenSubmap();
    }
    const NodeRecord& rec = nodes_->at(id);
    if (!rec.keyframe || !rec.features) return;
    ++stats_.keyframes;
    if (id >= map_nodes_) query(id, rec);
    addToOpenSubmap(id, rec);
}

void OrbSubmapERD::query(TNodeID id, const NodeRecord& rec) {
    if (catalog_->size() == 0) return;
    ++stats_.queries;
    const auto t0 = Clock::now();
    const Eigen::Isometry3d pose = poseOf(id);
    const double radius =
        params_.searchRadius + params_.driftPerMetre * (travel_[id] - travel_at_last_closure_);
    const double reachable = travel_[id] - params_.minTravelGap;
    const auto candidates =
        catalog_->candidates(pose.translation(), radius, rec.features->descriptors,
                             params_.nearCandidates, params_.similarCandidates, params_.minVotes,
                             [&](std::size_t s) { return submap_end_travel_[s] <= reachable; });
    Query q;
    q.node = id;
    q.candidates = candidates.size();
    q.retrievalMs = msSince(t0);
    stats_.retrievalMs += q.retrievalMs;

    std::optional<std::pair<vision::SubmapMatcher::Result, std::size_t>> best;
    for (const auto& c : candidates) {
        ++stats_.candidatesTried;
        const auto t1 = Clock::now();
        auto r = matcher_->match(catalog_->at(c.submap), *rec.features, rec.T_robot_camera, id + 1);
        const double ms = msSince(t1);
        stats_.matchMs += ms;
        stats_.phase1Ms += r.phase1Ms;
        stats_.phase2Ms += r.phase2Ms;
        q.slowestMatchMs = std::max(q.slowestMatchMs, ms);
        q.bestMatches = std::max(q.bestMatches, r.matches);
        q.bestInliers = std::max(q.bestInliers, r.inliers);
        if (r.success && (!best || r.inliers > best->first.inliers))
            best = std::make_pair(r, c.submap);
    }
    q.accepted = best.has_value();
    queries_.push_back(q);
    if (!best) return;
    const auto& [r, submap] = *best;
    const auto from = static_cast<TNodeID>(r.node);
    const bool strong = params_.strongInliers > 0 &&
                        r.inliers >= static_cast<std::size_t>(params_.strongInliers);
    registerClosure(
        from, id,
        closureConstraint(r.nodeToQuery, r.covariance, params_.minSigmaXY, params_.minSigmaYaw),
        records_.size(), strong, static_cast<double>(r.inliers));
    records_.push_back({from, id, submap, r.usedPhase2, r.inliers, r.phase2Inliers, r.nodeToQuery});
    ++stats_.accepted;
    stats_.phase2Used += r.usedPhase2;
    travel_at_last_closure_ = travel_[id];
}

void OrbSubmapERD::addToOpenSubmap(TNodeID id, const NodeRecord& rec) {
    const auto t0 = Clock::now();
    if (!open_) {
        open_ = std::make_shared<vision::FeatureSubmap>(params_.submap);
        open_first_ = id;
        open_travel_start_ = travel_[id];
        open_variance_ = 0;
    }
    open_->add(static_cast<std::int64_t>(id), poseOf(open_first_).inverse() * poseOf(id),
               rec.T_robot_camera, rec.features);
    stats_.buildMs += msSince(t0);
    if (open_->members().size() >= static_cast<std::size_t>(params_.submapMaxKeyframes) ||
        open_->size() >= params_.submapMaxFeatures) {
        closeOpenSubmap();
    }
}

void OrbSubmapERD::closeOpenSubmap() {
    if (!open_) return;
    if (!open_->empty() && open_->size() > 0) {
        catalog_->add(open_, poseOf(open_first_) * open_->centre());
        // (a loaded map's submaps are reachable from the first node of the run)
        const auto last = static_cast<std::size_t>(open_->lastNode());
        submap_end_travel_.push_back(last < map_nodes_ ? -INFINITY : travel_[last]);
        submap_first_.push_back(open_first_);
        ++stats_.submaps;
    }
    open_.reset();
}

void OrbSubmapERD::refreshCentres() {
    // Optimization moves nodes; the submaps' centres follow their first node.
    nodes_since_refresh_ = 0;
    for (std::size_t s = 0; s < catalog_->size(); ++s) {
        catalog_->setCentre(s, poseOf(submap_first_[s]) * catalog_->at(s).centre());
    }
}

JsonObject OrbSubmapERD::describe() const {
    JsonObject params;
    params.set("submap_max_keyframes", params_.submapMaxKeyframes)
        .set("submap_max_length", params_.submapMaxLength)
        .set("submap_max_sigma", params_.submapMaxSigma)
        .set("submap_max_features", params_.submapMaxFeatures)
        .set("min_travel_gap", params_.minTravelGap)
        .set("search_radius", params_.searchRadius)
        .set("drift_per_metre", params_.driftPerMetre)
        .set("near_candidates", params_.nearCandidates)
        .set("similar_candidates", params_.similarCandidates)
        .set("min_votes", params_.minVotes)
        .set("phase1_max_features", params_.matcher.phase1MaxFeatures)
        .set("phase1_min_inliers", params_.matcher.phase1.minInliers)
        .set("phase2_min_inliers", params_.matcher.phase2.minInliers)
        .set("phase1_fallback", params_.matcher.phase1Fallback)
        .set("phase1_fallback_min_inliers", params_.matcher.fallbackMinInliers)
        .set("relocation_strong_inliers", params_.strongInliers);
    JsonObject stats;
    stats.set("keyframes", stats_.keyframes)
        .set("submaps", stats_.submaps)
        .set("queries", stats_.queries)
        .set("candidates_tried", stats_.candidatesTried)
        .set("accepted", stats_.accepted)
        .set("phase2_used", stats_.phase2Used)
        .set("retrieval_ms_total", stats_.retrievalMs)
        .set("match_ms_total", stats_.matchMs)
        .set("phase1_ms_total", stats_.phase1Ms)
        .set("phase2_ms_total", stats_.phase2Ms)
        .set("submap_build_ms_total", stats_.buildMs);
    return JsonObject().set("class", getClassName()).set("params", params).set("stats", stats);
}

}  // namespace lodestone::graphslam
