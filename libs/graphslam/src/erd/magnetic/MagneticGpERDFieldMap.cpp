// MagneticGpERD, the field map: the last stretch of readings placed against every earlier
// reading near it, where the graph has them now (magnetic::FieldMapSearch). No sequence match
// is needed, so it also places a robot that walks beside its earlier passes rather than on
// them - where the field it reads is one no earlier pass read. The map is the readings
// anchored to their nodes (by travel): when the graph moves, the map moves with it.
#include <lodestone/graphslam/erd/magnetic/MagneticGpERD.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace lodestone::graphslam {

void MagneticGpERD::countVerdict(magnetic::FieldMapVerdict v) {
    switch (v) {
        case magnetic::FieldMapVerdict::Accepted: ++stats_.mapAccepted; break;
        case magnetic::FieldMapVerdict::NoFit: ++stats_.mapNoFit; break;
        case magnetic::FieldMapVerdict::NotAboveNull: ++stats_.mapNotAboveNull; break;
        case magnetic::FieldMapVerdict::Ambiguous: ++stats_.mapAmbiguous; break;
        case magnetic::FieldMapVerdict::TooLoose: ++stats_.mapTooLoose; break;
        case magnetic::FieldMapVerdict::GateTooWide: ++stats_.mapGateTooWide; break;
    }
}

void MagneticGpERD::matchFieldMap(const magnetic::Supernode& q) {
    const auto& fm = params_.fieldMap;
    const auto& samples = track_->samples();
    const std::size_t qEnd = q.last;
    const double sEnd = samples[qEnd - 1].s;
    if (sEnd - last_map_search_ < fm.every) return;
    const auto qNode = static_cast<std::size_t>(samples[qEnd - 1].node);
    if (constrained_[qNode]) return;  // a sequence match placed it just now
    // The query: the last `window` metres of this segment, every plane_subsample-th reading.
    std::size_t qBegin = qEnd - 1;
    while (qBegin > 0 && samples[qBegin - 1].segment == q.segment &&
           samples[qBegin - 1].s >= sEnd - fm.window)
        --qBegin;
    if (sEnd - samples[qBegin].s < 0.9 * fm.window) return;  // the segment is younger than that
    last_map_search_ = sEnd;
    ++stats_.mapSearches;
    // Where the robot can be: the pose uncertainty since the last closure plus the map's own
    // error (gate_floor), as for the sequence matcher's candidates. A gate wider than the
    // search may cover is not searched: a place outside could fit as well.
    const double floor2 = params_.uncertainty.floor * params_.uncertainty.floor;
    const Eigen::Matrix2d gate = path_.uncertainty.covariance(static_cast<TNodeID>(qNode)).topLeftCorner<2, 2>() +
                                 floor2 * Eigen::Matrix2d::Identity();
    const double gateReach = magnetic::gateRadius(gate, fm.search.gateChi2);
    if (gateReach > fm.search.maxRadius) {
        ++stats_.mapGateTooWide;
        return;
    }
    const auto sub = static_cast<std::size_t>(params_.planeSubsample);
    std::vector<Eigen::Vector2d> qp;
    std::vector<std::size_t> qi;
    for (std::size_t i = qBegin; i < qEnd; i += sub) {
        Eigen::Vector2d p;
        if (!positionAtTravel(samples[i].s, q.segment, p)) continue;
        qp.push_back(p);
        qi.push_back(i);
    }
    if (qp.size() < 3) {
        ++stats_.mapNoMap;
        return;
    }
    Eigen::Vector2d lo = qp.front(), hi = qp.front();
    for (const auto& p : qp) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    // The map: earlier readings of this segment (left min_travel_gap ago) that any move inside
    // the gate can bring the query near - within the gate plus three length scales.
    const double reach = gateReach + 3 * params_.gp.lengthScale;
    lo.array() -= reach;
    hi.array() += reach;
    const double newest = samples[qBegin].s - params_.minTravelGap;
    std::vector<Eigen::Vector2d> at;
    std::vector<std::size_t> ai;
    for (std::size_t i = 0; i < qBegin && samples[i].s <= newest; i += sub) {
        Eigen::Vector2d p;
        if (samples[i].segment != q.segment || !positionAtTravel(samples[i].s, q.segment, p)) continue;
        if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any()) continue;
        at.push_back(p);
        ai.push_back(i);
    }
    if (at.size() < qp.size() / 2) {
        ++stats_.mapNoMap;
        return;
    }
    // Beyond max_points, thinned evenly (the GP's cost is cubic in them).
    const std::size_t thin = (at.size() + static_cast<std::size_t>(fm.maxPoints) - 1) /
                             static_cast<std::size_t>(fm.maxPoints);
    const int C = track_->channels();
    const auto n = static_cast<Eigen::Index>((at.size() + thin - 1) / thin);
    Eigen::MatrixX2d P(n, 2);
    Eigen::MatrixXd Y(n, C);
    for (Eigen::Index r = 0; r < n; ++r) {
        const std::size_t k = static_cast<std::size_t>(r) * thin;
        P.row(r) = at[k].transpose();
        Y.row(r) = samples[ai[k]].value.cast<double>().transpose();
    }
    const auto m = static_cast<Eigen::Index>(qp.size());
    Eigen::MatrixX2d Q(m, 2);
    Eigen::MatrixXd V(m, C);
    for (Eigen::Index r = 0; r < m; ++r) {
        Q.row(r) = qp[static_cast<std::size_t>(r)].transpose();
        V.row(r) = samples[qi[static_cast<std::size_t>(r)]].value.cast<double>().transpose();
    }
    magnetic::GpHyperparameters h = params_.gp;
    if (fm.sigmaN > 0) h.sigmaN = fm.sigmaN;  // readings of different passes repeat this well
    magnetic::GaussianProcess2D gp(h);
    gp.fit(P, Y);
    const auto match = magnetic::searchFieldMap(gp, Q, V, gate, fm.search);
    countVerdict(match.verdict);
    MRPT_LOG_DEBUG_FMT(
        "field map at node %zu: %s (log evidence %.1f, nrms %.2f, move %.2f %.2f m %.3f rad, "
        "sigma %.3f %.3f m; %ld map readings)",
        qNode, magnetic::toString(match.verdict).c_str(), match.logEvidence,
        match.alignment.normalizedRms, match.alignment.delta[0], match.alignment.delta[1],
        match.alignment.delta[2], std::sqrt(match.alignment.covariance(0, 0)),
        std::sqrt(match.alignment.covariance(1, 1)), static_cast<long>(n));
    if (match.accepted()) addFieldMapEdges(q, match, qBegin, qNode, ai);
}

void MagneticGpERD::addFieldMapEdges(const magnetic::Supernode& q,
                                     const magnetic::FieldMapMatch& match, std::size_t qBegin,
                                     std::size_t qNode, const std::vector<std::size_t>& mapReadings) {
    const auto& samples = track_->samples();
    // Each query node moved as its readings were, tied to the nearest earlier node.
    Record rec;
    rec.querySupernode = q.id;
    rec.fieldMap = true;
    rec.plane = true;
    rec.planeDelta = match.alignment.delta;
    rec.normalizedRms = match.alignment.normalizedRms;
    rec.logRatio = match.logEvidence;
    std::vector<std::size_t> mapNodes;
    for (const std::size_t i : mapReadings) {
        if (mapNodes.empty() || mapNodes.back() != samples[i].node) mapNodes.push_back(samples[i].node);
    }
    const std::size_t firstNode = samples[qBegin].node;
    for (std::size_t qn = firstNode; qn <= qNode; ++qn) {
        if (constrained_[qn] || qn % static_cast<std::size_t>(params_.edgeEvery) != 0) continue;
        const auto here = positionOf(static_cast<TNodeID>(qn));
        const Eigen::Vector2d p(here.x, here.y);
        const Eigen::Vector2d moved = match.alignment.apply(p);
        std::size_t nearest = mapNodes.front();
        double best = std::numeric_limits<double>::infinity();
        for (const std::size_t k : mapNodes) {
            const auto t = positionOf(static_cast<TNodeID>(k));
            const double d = (Eigen::Vector2d(t.x, t.y) - moved).squaredNorm();
            if (d < best) {
                best = d;
                nearest = k;
            }
        }
        addMovedNodeEdge(qn, static_cast<TNodeID>(nearest), p, 0.0, match.alignment, rec);
    }
    commitEdges(rec);
}

}  // namespace lodestone::graphslam
