#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/erd/magnetic/MagneticCrossingERD.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <memory>

#include "../../Stopwatch.h"

namespace lodestone::graphslam {

MagneticCrossingERD::MagneticCrossingERD() { setClassName("MagneticCrossingERD"); }

void MagneticCrossingERD::configure(const mrpt::config::CConfigFileBase& ini) {
    config::IniSection s(ini, "MagneticCrossingERD", config::sourceName(ini));
    Params p = params_;
    p.sensorLabel = s.getString("sensor_label", p.sensorLabel);
    p.saturation = s.getDouble("saturation", p.saturation);
    p.stretchLength = s.getDouble("stretch_length", p.stretchLength);
    p.queryEvery = s.getDouble("query_every", p.queryEvery);
    p.minLoop = s.getDouble("min_loop", p.minLoop);
    p.minLogEvidence = s.getDouble("min_log_evidence", p.minLogEvidence);
    p.minSupport = s.getDouble("min_support", p.minSupport);
    p.convergedSigma = s.getDouble("converged_sigma", p.convergedSigma);
    p.convergedYawSigma =
        s.getDouble("converged_yaw_sigma_deg", p.convergedYawSigma * 180 / M_PI) * M_PI / 180;
    p.fitAfter = s.getDouble("fit_after", p.fitAfter);
    p.match.passSigma = s.getDouble("pass_sigma", p.match.passSigma);
    p.match.tailDof = s.getDouble("tail_dof", p.match.tailDof);
    p.match.maxOffset = s.getDouble("max_offset", p.match.maxOffset);
    p.match.maxYaw = s.getDouble("max_yaw_deg", p.match.maxYaw * 180 / M_PI) * M_PI / 180;
    p.sigmaFloor = s.getDouble("sigma_floor", p.sigmaFloor);
    p.grid.cell = s.getDouble("grid_cell", p.grid.cell);
    if (!(p.saturation > 0)) s.fail("saturation", "must be > 0");
    if (!(p.stretchLength > 0)) s.fail("stretch_length", "must be > 0");
    if (!(p.queryEvery > 0)) s.fail("query_every", "must be > 0");
    if (!(p.minLoop >= 0)) s.fail("min_loop", "must be >= 0");
    if (!std::isfinite(p.minLogEvidence)) s.fail("min_log_evidence", "must be a number");
    if (!(p.minSupport >= 0)) s.fail("min_support", "must be >= 0");
    if (!(p.convergedSigma >= 0)) s.fail("converged_sigma", "must be >= 0");
    if (!(p.convergedYawSigma > 0)) s.fail("converged_yaw_sigma_deg", "must be > 0");
    if (!(p.fitAfter > 0)) s.fail("fit_after", "must be > 0");
    if (!(p.match.passSigma >= 0)) s.fail("pass_sigma", "must be >= 0");
    if (!(p.match.tailDof >= 0)) s.fail("tail_dof", "must be >= 0 (0: Gaussian)");
    if (!(p.match.maxOffset > 0 && p.match.maxOffset <= 10))
        s.fail("max_offset", "must be in (0, 10]");
    if (!(p.match.maxYaw >= 0 && p.match.maxYaw <= M_PI))
        s.fail("max_yaw_deg", "must be in [0, 180]");
    if (!(p.sigmaFloor > 0)) s.fail("sigma_floor", "must be > 0");
    if (!(p.grid.cell > 0.005 && p.grid.cell <= 1)) s.fail("grid_cell", "must be in (0.005, 1]");
    s.finish();
    params_ = p;
}

bool MagneticCrossingERD::updateState(mrpt::obs::CActionCollection::Ptr,
                                      mrpt::obs::CSensoryFrame::Ptr, mrpt::obs::CObservation::Ptr) {
    const std::size_t before = stats_.closures;
    for (; seen_ < m_graph->nodes.size() && nodes_ && nodes_->has(seen_); ++seen_) onNode(seen_);
    return stats_.closures > before;
}

void MagneticCrossingERD::onNode(TNodeID id) {
    const NodeRecord& rec = nodes_->at(id);
    path_.addNode(id, *m_graph, *nodes_, params_.sensorLabel, params_.saturation,
                  [&](double s, const Eigen::Vector3d& b) {
                      // Averaged over a grid cell of travel: the map's resolution.
                      if (readings_.empty() || readings_.back().segment != rec.segment ||
                          s - readings_.back().travel >= params_.grid.cell)
                          readings_.push_back({id, s, rec.segment, Eigen::Vector3d::Zero(), 0});
                      auto& r = readings_.back();
                      r.field = (r.field * r.count + b) / (r.count + 1);
                      ++r.count;
                  });
    total_travel_ = path_.travel.back();
    if (id < map_nodes_) return;  // a loaded map's nodes: taken in, never queried from
    // The hyperparameters from the run's own readings, again each time its travel doubled.
    if (total_travel_ >= params_.fitAfter && total_travel_ >= 2 * fitted_at_) {
        fitted_at_ = total_travel_;
        fit();
    }
    if (!h_ || total_travel_ - last_query_ < params_.queryEvery || total_travel_ < next_allowed_)
        return;
    last_query_ = total_travel_;
    const auto t0 = Clock::now();
    query(id);
    stats_.queryMs.push_back(msSince(t0));
}

void MagneticCrossingERD::fit() {
    std::vector<double> travel;
    std::vector<int> segment;
    std::vector<Eigen::Vector3d> field;
    for (const auto& r : readings_) {
        const Eigen::Vector3d pose = path_.poseAt(*m_graph, r.node, r.travel);
        const double c = std::cos(pose.z()), s = std::sin(pose.z());
        travel.push_back(r.travel);
        segment.push_back(r.segment);
        field.emplace_back(c * r.field.x() - s * r.field.y(), s * r.field.x() + c * r.field.y(),
                           r.field.z());
    }
    const auto stretches = fieldFitStretches(travel, segment, field);
    if (stretches.empty()) return;
    const auto result =
        magnetic::fitHyperparameters(stretches, h_ ? *h_ : magnetic::GpHyperparameters{});
    // A length scale below the readings' spacing is not one they can show (a fit run off to
    // zero): the last fit stays.
    if (!result.hyperparameters.valid() || result.hyperparameters.lengthScale < params_.grid.cell)
        return;
    h_ = result.hyperparameters;
    stats_.fitted = *h_;
    ++stats_.fits;
}

void MagneticCrossingERD::query(TNodeID id) {
    ++stats_.queries;
    const int segment = path_.segment[id];
    const auto& anchorNode = m_graph->nodes.at(id);
    const Eigen::Vector3d anchor(anchorNode.x(), anchorNode.y(), anchorNode.yaw());
    std::size_t first = readings_.size();
    const auto stretch = recentStretch(segment, anchor, first);
    const Passes passes = earlierPasses(first, segment, anchor, stretch);
    const auto matches = matchPasses(id, anchor, stretch, passes);
    if (matches.empty()) {
        ++stats_.offMap;
        return;
    }
    decide(id, matches, passes);
}

std::vector<magnetic::StretchSample> MagneticCrossingERD::recentStretch(
    int segment, const Eigen::Vector3d& anchor, std::size_t& first) const {
    const mrpt::poses::CPose2D anchorPose(anchor.x(), anchor.y(), anchor.z());
    const double l = h_->lengthScale;
    // The stretch: this segment's readings of the last stretch_length, relative to the anchor.
    std::vector<magnetic::StretchSample> stretch;
    first = readings_.size();
    while (first > 0 && readings_[first - 1].segment == segment &&
           readings_[first - 1].travel >= total_travel_ - params_.stretchLength)
        --first;
    for (std::size_t i = first; i < readings_.size(); ++i) {
        const auto& r = readings_[i];
        const Eigen::Vector3d p = path_.poseAt(*m_graph, r.node, r.travel);
        const auto rel = mrpt::poses::CPose2D(p.x(), p.y(), p.z()) - anchorPose;
        stretch.push_back(
            {{rel.x(), rel.y(), rel.phi()}, r.field, std::min(1.0, params_.grid.cell / l)});
    }
    return stretch;
}

MagneticCrossingERD::Passes MagneticCrossingERD::earlierPasses(
    std::size_t first, int segment, const Eigen::Vector3d& anchor,
    const std::vector<magnetic::StretchSample>& stretch) const {
    const double l = h_->lengthScale;
    // The map: earlier readings in this frame, at least min_loop before the stretch, within
    // the search's reach of one of its readings (where the graph has them).
    const double near = params_.match.maxOffset + params_.grid.reachScales * l;
    const double reach = params_.stretchLength + near;
    std::vector<Eigen::Vector2d> placed;
    for (const auto& k : stretch)
        placed.push_back(anchor.head<2>() + Eigen::Rotation2Dd(anchor.z()) * k.pose.head<2>());
    Passes passes;
    auto& points = passes.points;
    for (std::size_t i = 0, last = 0; i < first; ++i) {
        const auto& r = readings_[i];
        if (!sameFrame(r.segment, segment)) continue;
        if (r.segment == segment &&
            r.travel > total_travel_ - params_.stretchLength - params_.minLoop)
            continue;
        const Eigen::Vector3d p = path_.poseAt(*m_graph, r.node, r.travel);
        if ((p.head<2>() - anchor.head<2>()).norm() > reach) continue;
        if (std::none_of(placed.begin(), placed.end(), [&](const Eigen::Vector2d& q) {
                return (q - p.head<2>()).squaredNorm() <= near * near;
            }))
            continue;
        if (!points.empty() && i != last + 1) passes.start.push_back(points.size());
        last = i;
        const double c = std::cos(p.z()), s = std::sin(p.z());
        points.push_back(p.head<2>());
        passes.fields.emplace_back(c * r.field.x() - s * r.field.y(),
                                   s * r.field.x() + c * r.field.y(), r.field.z());
        passes.nodeOf.push_back(r.node);
    }
    passes.start.push_back(points.size());
    return passes;
}

std::vector<MagneticCrossingERD::PassMatch> MagneticCrossingERD::matchPasses(
    TNodeID id, const Eigen::Vector3d& anchor, const std::vector<magnetic::StretchSample>& stretch,
    const Passes& passes) const {
    const double l = h_->lengthScale;
    const auto& points = passes.points;
    const auto& nodeOf = passes.nodeOf;
    const auto& passStart = passes.start;
    // Each earlier pass is a map of its own: within one pass the odometry is consistent, while
    // passes placed by a drifting graph disagree by their drift, and a field map of several
    // would be a field that is nowhere.
    std::vector<PassMatch> matches;
    // The maps' cells: a sixth of the length scale where the field is smoother than grid_cell's
    // (a field of 0.8 m, as on Kok's walks, needs no 5 cm raster).
    auto grid = params_.grid;
    grid.cell = std::max(grid.cell, l / 6);
    for (std::size_t k = 0; k + 1 < passStart.size(); ++k) {
        const std::size_t begin = passStart[k], end = passStart[k + 1];
        // A pass too short to hold min_support of the stretch is skipped unweighed.
        if (stretch.size() < 2 || end - begin < 2 ||
            double(end - begin) * std::min(1.0, params_.grid.cell / l) < params_.minSupport)
            continue;
        Eigen::MatrixX2d P(static_cast<Eigen::Index>(end - begin), 2);
        Eigen::MatrixX3d F(static_cast<Eigen::Index>(end - begin), 3);
        for (std::size_t i = begin; i < end; ++i) {
            P.row(static_cast<Eigen::Index>(i - begin)) = points[i].transpose();
            F.row(static_cast<Eigen::Index>(i - begin)) = passes.fields[i].transpose();
        }
        std::unique_ptr<magnetic::PlanarFieldGrid> map;
        try {
            map = std::make_unique<magnetic::PlanarFieldGrid>(P, F, *h_, grid);
        } catch (const std::invalid_argument&) {
            continue;
        }
        // The gate: the path's uncertainty relative to the pass's node nearest the anchor.
        std::size_t nearest = begin;
        for (std::size_t i = begin; i < end; ++i)
            if ((points[i] - anchor.head<2>()).squaredNorm() <
                (points[nearest] - anchor.head<2>()).squaredNorm())
                nearest = i;
        const Eigen::Matrix2d prior = path_.uncertainty.relativeGateCovariance(nodeOf[nearest], id);
        // Headings within three sigmas of both ends' heading uncertainty, at most max_yaw_deg.
        auto match = params_.match;
        match.step = std::max(match.step, grid.cell);
        match.fineStep = grid.cell;
        const double yawVariance = path_.uncertainty.covariance(id)(2, 2) +
                                   path_.uncertainty.covariance(nodeOf[nearest])(2, 2);
        match.maxYaw = std::min(match.maxYaw, 3 * std::sqrt(yawVariance) + match.yawStep);
        matches.push_back(
            {magnetic::matchStretch(*map, stretch, anchor, prior, match), begin, end});
    }
    return matches;
}

void MagneticCrossingERD::decide(TNodeID id, const std::vector<PassMatch>& matches,
                                 const Passes& passes) {
    const double l = h_->lengthScale;
    const auto& points = passes.points;
    const auto best = std::max_element(
        matches.begin(), matches.end(),
        [](const auto& a, const auto& b) { return a.m.logEvidence < b.m.logEvidence; });
    const auto& m = best->m;
    const double oneSigma = params_.convergedSigma > 0 ? params_.convergedSigma : 0.5 * l;
    if (m.support < params_.minSupport) {
        ++stats_.tooLittleSupport;
        return;
    }
    if (!(m.logEvidence >= params_.minLogEvidence)) {
        ++stats_.notDecisive;
        return;
    }
    if (!(m.positionSigma < oneSigma && m.yawSigma < params_.convergedYawSigma)) {
        ++stats_.notOnePlace;
        return;
    }
    // Another pass as decisive elsewhere: two places, not one.
    for (const auto& o : matches)
        if (&o != &*best && o.m.logEvidence >= params_.minLogEvidence &&
            (o.m.pose.head<2>() - m.pose.head<2>()).norm() > 3 * oneSigma) {
            ++stats_.ambiguous;
            return;
        }
    // From the earlier node nearest the matched place.
    std::size_t target = best->begin;
    for (std::size_t i = best->begin; i < best->end; ++i)
        if ((points[i] - m.pose.head<2>()).squaredNorm() <
            (points[target] - m.pose.head<2>()).squaredNorm())
            target = i;
    const TNodeID from = passes.nodeOf[target];
    const auto& t = m_graph->nodes.at(from);
    const auto z = closureFrom({t.x(), t.y(), t.yaw()}, m.pose, m.covariance, params_.sigmaFloor);
    const Eigen::Matrix3d cov = z.cov.asEigen();
    registerClosure(from, id, planarConstraint(z), stats_.closures, false, m.logEvidence);
    path_.pinClosure(id, t.yaw(), cov.topLeftCorner<2, 2>(), cov(2, 2));
    ++stats_.closures;
    // The next closure from readings this one did not use.
    next_allowed_ = total_travel_ + params_.stretchLength;
}

JsonObject MagneticCrossingERD::describe() const {
    JsonObject params;
    params.set("sensor_label", params_.sensorLabel)
        .set("stretch_length", params_.stretchLength)
        .set("query_every", params_.queryEvery)
        .set("min_loop", params_.minLoop)
        .set("min_log_evidence", params_.minLogEvidence)
        .set("min_support", params_.minSupport)
        .set("converged_sigma", params_.convergedSigma)
        .set("converged_yaw_sigma_deg", params_.convergedYawSigma * 180 / M_PI)
        .set("fit_after", params_.fitAfter)
        .set("pass_sigma", params_.match.passSigma)
        .set("tail_dof", params_.match.tailDof)
        .set("max_offset", params_.match.maxOffset)
        .set("max_yaw_deg", params_.match.maxYaw * 180 / M_PI)
        .set("sigma_floor", params_.sigmaFloor)
        .set("grid_cell", params_.grid.cell);
    JsonObject stats;
    path_.describeCounts(stats)
        .set("queries", stats_.queries)
        .set("off_map", stats_.offMap)
        .set("too_little_support", stats_.tooLittleSupport)
        .set("not_decisive", stats_.notDecisive)
        .set("not_one_place", stats_.notOnePlace)
        .set("ambiguous", stats_.ambiguous)
        .set("closures", stats_.closures)
        .set("fits", stats_.fits)
        .set("fitted_sigma_f", stats_.fitted.sigmaF)
        .set("fitted_length_scale", stats_.fitted.lengthScale)
        .set("fitted_sigma_n", stats_.fitted.sigmaN);
    describeQueryTimes(stats, stats_.queryMs);
    JsonObject out;
    out.set("class", getClassName()).set("params", params).set("stats", stats);
    return out;
}

}  // namespace lodestone::graphslam
