#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/erd/magnetic/MagneticGpERD.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "../../Stopwatch.h"

namespace lodestone::graphslam {

MagneticGpERD::MagneticGpERD() {
    setClassName("MagneticGpERD");
    rebuild();
}

void MagneticGpERD::rebuild() {
    track_ = std::make_unique<magnetic::SupernodeTrack>(params_.track,
                                                        magnetic::channelsOf(params_.mode));
    index_ = std::make_unique<magnetic::SupernodeIndex>(
        track_->channels(), track_->samplesPerSupernode(), params_.indexBins);
    matcher_ = std::make_unique<magnetic::BundleMatcher>(params_.bundle);
    path_ = MagneticPath(params_.uncertainty);
}

void MagneticGpERD::configure(const mrpt::config::CConfigFileBase& ini) {
    config::IniSection s(ini, "MagneticGpERD", config::sourceName(ini));
    Params p = params_;  // all or nothing
    try {
        p.mode = magnetic::parseFieldMode(s.getString("field_mode", magnetic::toString(p.mode)));
    } catch (const std::invalid_argument& e) {
        s.fail("field_mode", e.what());
    }
    p.sensorLabel = s.getString("sensor_label", p.sensorLabel);
    p.saturation = s.getDouble("saturation", p.saturation);
    p.track.step = s.getDouble("resample_step", p.track.step);
    p.track.length = s.getDouble("supernode_length", p.track.length);
    p.track.stride = s.getDouble("supernode_stride", p.track.stride);
    p.indexBins = s.getInt("index_bins", p.indexBins);
    p.candidates = static_cast<std::size_t>(s.getInt("candidates", static_cast<int>(p.candidates)));
    p.maxCost = s.getDouble("max_cost", p.maxCost);
    p.minSpread = s.getDouble("min_spread", p.minSpread);
    p.minTravelGap = s.getDouble("min_travel_gap", p.minTravelGap);
    p.gateChi2 = s.getDouble("gate_chi2", p.gateChi2);
    p.uncertainty.headingBias = s.getDouble("gate_heading_drift", p.uncertainty.headingBias);
    p.uncertainty.floor = s.getDouble("gate_floor", p.uncertainty.floor);
    p.sameplaceRadius = s.getDouble("same_place_radius", p.sameplaceRadius);
    p.ambiguityLogRatio = s.getDouble("ambiguity_log_ratio", p.ambiguityLogRatio);
    if (!(p.gateChi2 > 0)) s.fail("gate_chi2", "must be > 0");
    if (!(p.uncertainty.headingBias >= 0)) s.fail("gate_heading_drift", "must be >= 0");
    if (!(p.uncertainty.floor > 0)) s.fail("gate_floor", "must be > 0");
    if (!(p.sameplaceRadius > 0)) s.fail("same_place_radius", "must be > 0");
    if (!(p.ambiguityLogRatio >= 0)) s.fail("ambiguity_log_ratio", "must be >= 0");
    p.bundle.minChain =
        static_cast<std::size_t>(s.getInt("min_chain", static_cast<int>(p.bundle.minChain)));
    p.bundle.offsetTolerance = s.getDouble("offset_tolerance", p.bundle.offsetTolerance);
    p.gpWindow = s.getDouble("gp_window", p.gpWindow);
    p.gp.sigmaF = s.getDouble("gp_sigma_f", p.gp.sigmaF);
    p.gp.lengthScale = s.getDouble("gp_length_scale", p.gp.lengthScale);
    p.gp.sigmaN = s.getDouble("gp_sigma_n", p.gp.sigmaN);
    p.gp.sigmaC = s.getDouble("gp_sigma_c", p.gp.sigmaC);
    p.shift.maxShift = s.getDouble("max_shift", p.shift.maxShift);
    p.shift.step = s.getDouble("shift_step", p.shift.step);
    p.maxNormalizedRms = s.getDouble("max_normalized_rms", p.maxNormalizedRms);
    {
        const std::string a =
            s.getString("alignment", p.alignment == Params::Alignment::Plane ? "plane" : "path");
        if (a != "path" && a != "plane") s.fail("alignment", "'" + a + "' is not path | plane");
        p.alignment = a == "plane" ? Params::Alignment::Plane : Params::Alignment::Path;
    }
    p.planeMargin = s.getDouble("plane_margin", p.planeMargin);
    p.planeSubsample = s.getInt("plane_subsample", p.planeSubsample);
    p.plane.priorSigmaXY = s.getDouble("plane_prior_sigma", p.plane.priorSigmaXY);
    p.plane.priorSigmaYaw =
        s.getDouble("plane_prior_sigma_yaw_deg", p.plane.priorSigmaYaw * 180 / M_PI) * M_PI / 180;
    p.plane.maxShift = s.getDouble("plane_max_shift", p.plane.maxShift);
    if (!(p.planeMargin >= 0)) s.fail("plane_margin", "must be >= 0");
    if (p.planeSubsample < 1) s.fail("plane_subsample", "must be >= 1");
    if (!(p.plane.priorSigmaXY > 0) || !(p.plane.priorSigmaYaw > 0))
        s.fail("plane_prior_sigma", "prior sigmas must be > 0");
    if (!(p.plane.maxShift > 0)) s.fail("plane_max_shift", "must be > 0");
    p.fieldMap.enabled = s.getBool("map_search", p.fieldMap.enabled);
    p.fieldMap.every = s.getDouble("map_search_every", p.fieldMap.every);
    p.fieldMap.window = s.getDouble("map_window", p.fieldMap.window);
    p.fieldMap.maxPoints = s.getInt("map_max_points", p.fieldMap.maxPoints);
    p.fieldMap.sigmaN = s.getDouble("map_sigma_n", p.fieldMap.sigmaN);
    p.fieldMap.search.maxRadius = s.getDouble("map_search_radius", p.fieldMap.search.maxRadius);
    p.fieldMap.search.gridStep = s.getDouble("map_grid_step", p.fieldMap.search.gridStep);
    p.fieldMap.search.minLogRatio = s.getDouble("map_min_log_ratio", p.fieldMap.search.minLogRatio);
    p.fieldMap.search.maxSigma = s.getDouble("map_max_sigma", p.fieldMap.search.maxSigma);
    if (!(p.fieldMap.every > 0)) s.fail("map_search_every", "must be > 0");
    if (!(p.fieldMap.window > 4 * p.track.step)) s.fail("map_window", "must be > 4 x resample_step");
    if (p.fieldMap.maxPoints < 10) s.fail("map_max_points", "must be >= 10");
    if (!(p.fieldMap.search.maxRadius > 0)) s.fail("map_search_radius", "must be > 0");
    if (!(p.fieldMap.search.gridStep > 0) ||
        !(p.fieldMap.search.gridStep < p.fieldMap.search.maxRadius))
        s.fail("map_grid_step", "must be in (0, map_search_radius)");
    if (!(p.fieldMap.search.minLogRatio >= 0)) s.fail("map_min_log_ratio", "must be >= 0");
    if (!(p.fieldMap.search.maxSigma > 0)) s.fail("map_max_sigma", "must be > 0");
    p.edgeEvery = s.getInt("edge_every", p.edgeEvery);
    p.edgesShareAlignment = s.getBool("edges_share_alignment", p.edgesShareAlignment);
    p.sigmaAlong = s.getDouble("sigma_along", p.sigmaAlong);
    p.sigmaCross = s.getDouble("sigma_cross", p.sigmaCross);
    p.sigmaYaw = s.getDouble("sigma_yaw_deg", p.sigmaYaw * 180 / M_PI) * M_PI / 180;
    if (!(p.track.step > 0)) s.fail("resample_step", "must be > 0");
    if (!(p.track.length > 2 * p.track.step))
        s.fail("supernode_length", "must be > 2 x resample_step");
    if (!(p.track.stride >= p.track.step)) s.fail("supernode_stride", "must be >= resample_step");
    if (p.indexBins < 1) s.fail("index_bins", "must be >= 1");
    if (p.candidates < 1) s.fail("candidates", "must be >= 1");
    if (!(p.maxCost > 0)) s.fail("max_cost", "must be > 0");
    if (p.bundle.minChain < 1) s.fail("min_chain", "must be >= 1");
    if (!p.gp.valid()) s.fail("gp_sigma_f", "GP hyperparameters must be > 0");
    if (!(p.shift.step > 0) || !(p.shift.maxShift > p.shift.step))
        s.fail("max_shift", "must be > shift_step > 0");
    if (p.edgeEvery < 1) s.fail("edge_every", "must be >= 1");
    if (!(p.sigmaAlong > 0) || !(p.sigmaCross > 0) || !(p.sigmaYaw > 0))
        s.fail("sigma_cross", "sigmas must be > 0");
    if (!(p.saturation > 0)) s.fail("saturation", "must be > 0");
    s.finish();
    // The field map judges its fits as the other alignments do.
    p.fieldMap.search.gateChi2 = p.gateChi2;
    p.fieldMap.search.maxNormalizedRms = p.maxNormalizedRms;
    p.fieldMap.search.plane = p.plane;
    p.fieldMap.search.distinctRadius = p.sameplaceRadius;
    p.fieldMap.search.ambiguityLogRatio = p.ambiguityLogRatio;
    params_ = p;
    rebuild();
}

bool MagneticGpERD::updateState(mrpt::obs::CActionCollection::Ptr, mrpt::obs::CSensoryFrame::Ptr,
                                mrpt::obs::CObservation::Ptr) {
    const std::size_t before = stats_.edges;
    for (; seen_ < m_graph->nodes.size() && nodes_ && nodes_->has(seen_); ++seen_) onNode(seen_);
    return stats_.edges > before;
}

mrpt::math::TPoint2D MagneticGpERD::positionOf(TNodeID id) const {
    const auto& p = m_graph->nodes.at(id);
    return {p.x(), p.y()};
}

void MagneticGpERD::onNode(TNodeID id) {
    const double heading = m_graph->nodes.at(id).yaw();
    const int segment = nodes_->at(id).segment;
    constrained_.push_back(false);
    path_.addNode(id, *m_graph, *nodes_, params_.sensorLabel, params_.saturation,
                  [&](double s, const Eigen::Vector3d& b) {
                      for (const auto& sn : track_->add(
                               s, magnetic::fieldFeature(b, heading, params_.mode), id, segment)) {
                          query(sn);
                      }
                  });
}

void MagneticGpERD::query(const magnetic::Supernode& q) {
    const auto& samples = track_->samples();
    if (samples[q.last - 1].node < map_nodes_) {
        // A loaded map's supernode: indexed, never a query.
        previous_supernode_ = q.id;
        unindexed_.push_back(q.id);
        return;
    }
    const auto t0 = Clock::now();
    ++stats_.supernodes;
    const bool follows = previous_supernode_ && *previous_supernode_ + 1 == q.id &&
                         track_->supernodes()[*previous_supernode_].segment == q.segment;
    previous_supernode_ = q.id;
    std::vector<magnetic::SupernodeMatch> matches;
    Trace trace;
    const TNodeID qNode = static_cast<TNodeID>(samples[q.last - 1].node);
    const double qTravel = samples[q.first].s;
    // Supernodes join the index once the robot is min_travel_gap past them: the nearest ones
    // in field space would otherwise be the query's own overlapping predecessors.
    // (a loaded map's join at once)
    const auto indexable = [&](const magnetic::Supernode& s) {
        const auto& last = samples[s.last - 1];
        return last.node < map_nodes_ || last.s <= qTravel - params_.minTravelGap;
    };
    while (!unindexed_.empty() && indexable(track_->supernodes()[unindexed_.front()])) {
        index_->add(track_->supernodes()[unindexed_.front()]);
        unindexed_.pop_front();
    }
    if (q.spread < params_.minSpread) {
        ++stats_.flatSupernodes;
        trace.flat = true;
    } else {
        const auto here = positionOf(qNode);
        for (const std::size_t id : index_->nearest(q, params_.candidates)) {
            if (truth_) trace.shortlist.push_back(id);
            const auto& t = track_->supernodes()[id];
            // Where the robot can be: the two supernodes' ends inside the gate of the pose
            // uncertainty. Across segments the graph's positions are not comparable until
            // they joined (kidnap, a run started in a map): everywhere.
            if (sameFrame(t.segment, q.segment)) {
                const auto there = positionOf(static_cast<TNodeID>(samples[t.last - 1].node));
                const Eigen::Vector2d d(here.x - there.x, here.y - there.y);
                if (path_.uncertainty.gateDistance2(qNode, d) > params_.gateChi2) {
                    ++stats_.gatedOut;
                    continue;
                }
            }
            const auto [cost, first] = track_->alignedCost(q, t, track_->halfStrideSamples());
            if (cost > params_.maxCost) continue;
            matches.push_back({q.id, id, samples[first].s - qTravel, cost});
        }
    }
    unindexed_.push_back(q.id);
    if (!matches.empty()) ++stats_.matchedSupernodes;
    const auto bundles = matcher_->add(q.id, matches, follows);
    if (!bundles.empty()) {
        ++stats_.bundles;
        // Several places: the same place seen on several earlier passes lies together (fine);
        // look-alike places do not - the likelier by the GP wins, if clearly.
        const auto places = groupByPlace(bundles);
        if (truth_) trace.places = places;
        // Every place is scored on the same query readings (the shortest window), so that
        // their likelihoods compare.
        std::size_t qBegin = 0;
        for (const auto& place : places) qBegin = std::max(qBegin, windowStart(place.front()));
        std::optional<PathFit> best;
        std::size_t bestPlace = 0;
        double runnerUp = -std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k < places.size(); ++k) {
            auto fit = fitAlongPath(places[k].front(), qBegin);
            if (!fit) continue;
            if (!best || fit->shift.logLikelihood > best->shift.logLikelihood) {
                if (best) runnerUp = best->shift.logLikelihood;
                best = fit;
                bestPlace = k;
            } else {
                runnerUp = std::max(runnerUp, fit->shift.logLikelihood);
            }
        }
        if (!best) {
            ++stats_.gpRejected;
            trace.outcome = Trace::Outcome::GpRejected;
        } else if ((best->shift.logLikelihood - runnerUp) /
                       std::max(1.0, best->shift.normalizedRms * best->shift.normalizedRms) <
                   params_.ambiguityLogRatio) {
            // (a fit worse than the GP's noise model - normalized RMS over 1 - makes every
            // likelihood difference less telling: the ratio is deflated by that dispersion)
            ++stats_.ambiguous;
            trace.outcome = Trace::Outcome::Ambiguous;
        } else {
            if (places.size() > 1) ++stats_.resolved;
            const std::size_t edges = stats_.edges;
            align(places[bestPlace], *best);
            trace.outcome = Trace::Outcome::Aligned;
            trace.chosen = bestPlace;
            trace.edges = stats_.edges > edges;
        }
    }
    if (params_.fieldMap.enabled) matchFieldMap(q);
    stats_.queryMs.push_back(msSince(t0));
    if (truth_) diagnose(q, trace);  // (after the timing: diagnostics are not the decider's cost)
}

std::vector<std::vector<magnetic::BundleMatch>> MagneticGpERD::groupByPlace(
    const std::vector<magnetic::BundleMatch>& bundles) const {
    const auto& samples = track_->samples();
    const auto where = [&](const magnetic::BundleMatch& b) {
        return positionOf(
            static_cast<TNodeID>(samples[track_->supernodes()[b.lastTarget].last - 1].node));
    };
    std::vector<std::vector<magnetic::BundleMatch>> places;
    for (const auto& b : bundles) {
        const auto p = where(b);
        const auto same = std::find_if(places.begin(), places.end(), [&](const auto& place) {
            return (where(place.front()) - p).norm() <= params_.sameplaceRadius;
        });
        if (same == places.end()) {
            places.push_back({b});
        } else {
            same->push_back(b);
        }
    }
    return places;
}

JsonObject MagneticGpERD::describe() const {
    JsonObject params;
    params.set("field_mode", magnetic::toString(params_.mode))
        .set("sensor_label", params_.sensorLabel)
        .set("resample_step", params_.track.step)
        .set("supernode_length", params_.track.length)
        .set("supernode_stride", params_.track.stride)
        .set("max_cost", params_.maxCost)
        .set("gate_chi2", params_.gateChi2)
        .set("gate_heading_drift", params_.uncertainty.headingBias)
        .set("gate_floor", params_.uncertainty.floor)
        .set("same_place_radius", params_.sameplaceRadius)
        .set("ambiguity_log_ratio", params_.ambiguityLogRatio)
        .set("min_spread", params_.minSpread)
        .set("min_chain", params_.bundle.minChain)
        .set("gp_window", params_.gpWindow)
        .set("gp_sigma_f", params_.gp.sigmaF)
        .set("gp_length_scale", params_.gp.lengthScale)
        .set("gp_sigma_n", params_.gp.sigmaN)
        .set("gp_sigma_c", params_.gp.sigmaC)
        .set("max_shift", params_.shift.maxShift)
        .set("edge_every", params_.edgeEvery)
        .set("edges_share_alignment", params_.edgesShareAlignment)
        .set("alignment", params_.alignment == Params::Alignment::Plane ? "plane" : "path")
        .set("map_search", params_.fieldMap.enabled)
        .set("map_search_every", params_.fieldMap.every)
        .set("map_window", params_.fieldMap.window)
        .set("map_search_radius", params_.fieldMap.search.maxRadius)
        .set("map_min_log_ratio", params_.fieldMap.search.minLogRatio)
        .set("map_sigma_n", params_.fieldMap.sigmaN);
    JsonObject stats;
    path_.describeCounts(stats)
        .set("supernodes", stats_.supernodes)
        .set("flat_supernodes", stats_.flatSupernodes)
        .set("matched_supernodes", stats_.matchedSupernodes)
        .set("gated_out", stats_.gatedOut)
        .set("bundles", stats_.bundles)
        .set("ambiguous_bundles", stats_.ambiguous)
        .set("resolved_by_likelihood", stats_.resolved)
        .set("gp_rejected", stats_.gpRejected)
        .set("alignments", stats_.alignments)
        .set("plane_rejected", stats_.planeRejected)
        .set("edges", stats_.edges)
        .set("map_searches", stats_.mapSearches)
        .set("map_gate_too_wide", stats_.mapGateTooWide)
        .set("map_no_map", stats_.mapNoMap)
        .set("map_no_fit", stats_.mapNoFit)
        .set("map_not_above_null", stats_.mapNotAboveNull)
        .set("map_ambiguous", stats_.mapAmbiguous)
        .set("map_too_loose", stats_.mapTooLoose)
        .set("map_accepted", stats_.mapAccepted);
    describeQueryTimes(stats, stats_.queryMs);
    JsonObject out;
    out.set("class", getClassName()).set("params", params).set("stats", stats);
    if (truth_) {
        std::vector<std::string> names;
        for (int k = 0; k <= static_cast<int>(TruthStage::Aligned); ++k)
            names.push_back(toString(static_cast<TruthStage>(k)));
        out.set("truth_funnel", describeFunnel(funnel_, names,
                                               static_cast<int>(TruthStage::NotShortlisted),
                                               params_.gateChi2));
    }
    return out;
}

}  // namespace lodestone::graphslam
