#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/magnetic/MagneticWindowERD.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "../Stopwatch.h"

namespace lodestone::graphslam {

using magnetic::WindowDirection;

MagneticWindowERD::MagneticWindowERD() {
    setClassName("MagneticWindowERD");
    rebuild();
}

void MagneticWindowERD::rebuild() {
    params_.noise.step = params_.step;
    sensors_.clear();
    mirror_.clear();
    poses_.clear();
    n_ = magnetic::SupernodeTrack({params_.step, params_.window, params_.step}, 3)
             .samplesPerSupernode();
    path_ = MagneticPath(params_.uncertainty);
}

void MagneticWindowERD::configure(const mrpt::config::CConfigFileBase& ini) {
    config::IniSection s(ini, "MagneticWindowERD", config::sourceName(ini));
    Params p = params_;  // all or nothing
    p.sensorLabel = s.getString("sensor_label", p.sensorLabel);
    p.mirrorSensors = s.getBool("mirror_sensors", p.mirrorSensors);
    p.saturation = s.getDouble("saturation", p.saturation);
    p.step = s.getDouble("resample_step", p.step);
    p.window = s.getDouble("window_length", p.window);
    p.queryEvery = s.getDouble("query_every", p.queryEvery);
    p.noise.sigma = s.getDouble("window_sigma", p.noise.sigma);
    p.noise.biasSigma = s.getDouble("window_bias_sigma", p.noise.biasSigma);
    p.noise.trendSigma = s.getDouble("window_trend_sigma", p.noise.trendSigma);
    p.lengthScale = s.getDouble("gp_length_scale", p.lengthScale);
    p.nullOdds = s.getDouble("null_odds", p.nullOdds);
    p.minTravelGap = s.getDouble("min_travel_gap", p.minTravelGap);
    p.gateChi2 = s.getDouble("gate_chi2", p.gateChi2);
    p.uncertainty.headingBias = s.getDouble("gate_heading_drift", p.uncertainty.headingBias);
    p.uncertainty.floor = s.getDouble("gate_floor", p.uncertainty.floor);
    p.quantile = s.getDouble("test_quantile", p.quantile);
    p.minPosterior = s.getDouble("min_posterior", p.minPosterior);
    p.distinctRadius = s.getDouble("distinct_radius", p.distinctRadius);
    p.closureEvery = s.getDouble("closure_every", p.closureEvery);
    p.confirm = s.getBool("confirm", p.confirm);
    p.sigmaAlongFloor = s.getDouble("sigma_along_floor", p.sigmaAlongFloor);
    p.sigmaCross = s.getDouble("sigma_cross", p.sigmaCross);
    p.turnFloorDeg = s.getDouble("turn_floor_deg", p.turnFloorDeg);
    if (!(p.saturation > 0)) s.fail("saturation", "must be > 0");
    if (!(p.step > 0)) s.fail("resample_step", "must be > 0");
    if (!(p.window >= 4 * p.step)) s.fail("window_length", "must be >= 4 x resample_step");
    if (!(p.queryEvery > 0)) s.fail("query_every", "must be > 0");
    if (!(p.noise.sigma > 0)) s.fail("window_sigma", "must be > 0");
    if (!(p.noise.biasSigma >= 0)) s.fail("window_bias_sigma", "must be >= 0");
    if (!(p.noise.trendSigma >= 0)) s.fail("window_trend_sigma", "must be >= 0");
    if (!(p.lengthScale > 0)) s.fail("gp_length_scale", "must be > 0");
    if (!(p.nullOdds > 0)) s.fail("null_odds", "must be > 0");
    if (!(p.minTravelGap > p.window)) s.fail("min_travel_gap", "must be > window_length");
    if (!(p.gateChi2 > 0)) s.fail("gate_chi2", "must be > 0");
    if (!(p.uncertainty.headingBias >= 0)) s.fail("gate_heading_drift", "must be >= 0");
    if (!(p.uncertainty.floor > 0)) s.fail("gate_floor", "must be > 0");
    if (!(p.quantile > 0.5 && p.quantile < 1)) s.fail("test_quantile", "must be in (0.5, 1)");
    if (!(p.minPosterior > 0.5 && p.minPosterior < 1))
        s.fail("min_posterior", "must be in (0.5, 1)");
    if (!(p.distinctRadius > 0)) s.fail("distinct_radius", "must be > 0");
    if (!(p.closureEvery >= 0)) s.fail("closure_every", "must be >= 0");
    if (!(p.sigmaAlongFloor > 0) || !(p.sigmaCross > 0) || !(p.turnFloorDeg >= 0))
        s.fail("sigma_cross", "sigmas must be > 0");
    s.finish();
    params_ = p;
    rebuild();
}

bool MagneticWindowERD::updateState(mrpt::obs::CActionCollection::Ptr,
                                    mrpt::obs::CSensoryFrame::Ptr, mrpt::obs::CObservation::Ptr) {
    const std::size_t before = stats_.edges;
    for (; seen_ < m_graph->nodes.size() && nodes_ && nodes_->has(seen_); ++seen_) onNode(seen_);
    return stats_.edges > before;
}

void MagneticWindowERD::onNode(TNodeID id) {
    const int segment = nodes_->at(id).segment;
    // (the graph's nodes are never erased: their addresses hold, their values follow the solves)
    poses_.push_back(&m_graph->nodes.at(id));
    path_.addNode(
        id, *m_graph, *nodes_, params_.saturation,
        [&](const MagneticSample& m) { return takeReading(m); },
        [&](const MagneticSample& m, double s, const Eigen::Vector3d& b) {
            auto& track = *sensors_.at(m.sensorLabel).track;
            const auto windows = track.add(s, b, id, segment);
            if (m.sensorLabel != params_.sensorLabel) return;  // the mirror's: stored only
            for (const auto& w : windows) {
                const double end = track.samples()[w.last - 1].s;
                if (end - lastQuery_ + 1e-9 < params_.queryEvery) continue;
                lastQuery_ = end;
                query(w.first);
            }
        });
}

Eigen::Vector2d MagneticWindowERD::positionAtSample(const magnetic::SupernodeTrack& track,
                                                    std::size_t i) const {
    // A sample lies in its node's interval: between node - 1 and node, by travel.
    const auto& sample = track.samples()[i];
    const auto k = static_cast<TNodeID>(sample.node);
    const auto& b = *poses_[k];
    if (k == 0 || path_.segment[k - 1] != path_.segment[k] ||
        path_.travel[k] <= path_.travel[k - 1])
        return {b.x(), b.y()};
    const auto& a = *poses_[k - 1];
    const double f = std::clamp(
        (sample.s - path_.travel[k - 1]) / (path_.travel[k] - path_.travel[k - 1]), 0.0, 1.0);
    return {a.x() + f * (b.x() - a.x()), a.y() + f * (b.y() - a.y())};
}

void MagneticWindowERD::compareAt(const magnetic::SupernodeTrack& track, std::size_t c,
                                  WindowDirection direction, std::size_t first, const Prior& prior,
                                  std::vector<Candidate>& out) const {
    const auto& samples = track.samples();
    const auto& query = queried().samples();
    // Forward: the window ending at c; backward: the window starting at c, read in reverse.
    std::size_t start = 0;
    if (direction == WindowDirection::Forward) {
        if (c + 1 < n_ || samples[c + 1 - n_].segment != samples[c].segment) return;
        start = c + 1 - n_;
    } else {
        if (c + n_ > samples.size() || samples[c + n_ - 1].segment != samples[c].segment ||
            samples[c + n_ - 1].s > query[first + n_ - 1].s - params_.minTravelGap)
            return;
        start = c;
    }
    Candidate k;
    k.track = &track;
    k.sample = c;
    k.direction = direction;
    k.fit = magnetic::compareWindows(query, first, samples, start, n_, direction, params_.noise,
                                     prior.turn, prior.turnVariance);
    k.gate2 = prior.gate2;
    k.total = k.fit.chi2 + prior.gate2;
    out.push_back(k);
}

MagneticWindowERD::Prior MagneticWindowERD::priorAt(const magnetic::SupernodeTrack& track,
                                                    std::size_t c, TNodeID qNode,
                                                    const Eigen::Vector2d& here) const {
    const auto& samples = track.samples();
    Prior p;
    if (samples[c].segment != path_.segment[qNode]) return p;
    // Where the robot can be, and which way it faces, under the pose uncertainty relative to
    // the target. Across a kidnap the graph knows neither: everywhere, any way.
    const auto target = static_cast<TNodeID>(samples[c].node);
    p.gate2 =
        path_.uncertainty.relativeGateDistance2(target, qNode, here - positionAtSample(track, c));
    p.turn = poses_[qNode]->yaw() - poses_[target]->yaw();
    const double turnFloor = params_.turnFloorDeg * M_PI / 180;
    p.turnVariance = path_.uncertainty.covariance(qNode)(2, 2) + turnFloor * turnFloor;
    return p;
}

void MagneticWindowERD::query(std::size_t first) {
    const auto t0 = Clock::now();
    ++stats_.queries;
    const auto& samples = queried().samples();
    const std::size_t newest = first + n_ - 1;
    const double dof = 3.0 * double(n_);
    Outcome out;
    const double excitation = magnetic::windowExcitation(samples, first, n_, params_.noise.sigma);
    out.flat = excitation < magnetic::chiSquareQuantile(dof - 3, params_.quantile);
    std::vector<Candidate> candidates;
    if (out.flat) {
        ++stats_.flat;  // a flat field matches anywhere
    } else {
        const auto qNode = static_cast<TNodeID>(samples[newest].node);
        const Eigen::Vector2d here = positionAtSample(queried(), newest);
        // Every stored reading the robot left at least min_travel_gap ago, inside the gate:
        // forward on the queried sensor's track, backward on its mirror's.
        const auto scan = [&](const magnetic::SupernodeTrack& track, bool forward, bool backward) {
            const auto& stored = track.samples();
            for (std::size_t c = 0;
                 c < stored.size() && stored[c].s <= samples[newest].s - params_.minTravelGap;
                 ++c) {
                const Prior p = priorAt(track, c, qNode, here);
                if (p.gate2 > params_.gateChi2) continue;
                if (forward) compareAt(track, c, WindowDirection::Forward, first, p, candidates);
                if (backward) compareAt(track, c, WindowDirection::Backward, first, p, candidates);
            }
        };
        if (&mirrored() == &queried()) {
            scan(queried(), true, true);
        } else {
            scan(queried(), true, false);
            scan(mirrored(), false, true);
        }
        decide(first, excitation, candidates, out);
    }
    stats_.queryMs.push_back(msSince(t0));
    if (truth_) {  // (after the timing: diagnostics are not the decider's cost)
        const auto record = diagnose(first, out);
        // (a pending closure made later marks its query's record then)
        if (record && !pending_.empty() && pending_.back().query == samples[newest].node &&
            !out.closed)
            pending_.back().truthRecord = record;
    }
}

void MagneticWindowERD::decide(std::size_t first, double excitation,
                               std::vector<Candidate>& candidates, Outcome& out) {
    const double dof = 3.0 * double(n_);
    if (candidates.empty()) {
        ++stats_.noCandidate;
        return;
    }
    out.best =
        *std::min_element(candidates.begin(), candidates.end(),
                          [](const Candidate& a, const Candidate& b) { return a.total < b.total; });
    if (out.best->fit.chi2 > magnetic::chiSquareQuantile(dof, params_.quantile)) {
        ++stats_.noFit;
        return;
    }
    // The null's field amplitude is this window's own: its spread about its mean, the reading
    // noise (half the difference's variance) taken out. A stretch that varies little is no
    // strong evidence when it matches another that varies little.
    const double s2 = params_.noise.sigma * params_.noise.sigma;
    const double spread2 = excitation * s2 / (dof - 3) - 0.5 * s2;
    const magnetic::WindowNullModel null(n_, params_.noise, std::sqrt(std::max(spread2, 1e-6)),
                                         params_.lengthScale);
    out.posterior = placePosterior(*out.best, candidates, first, null);
    if (out.posterior < params_.minPosterior) {
        ++stats_.ambiguous;
        return;
    }
    ++stats_.accepted;
    if (auto c = measureClosure(*out.best, candidates, first)) {
        out.closed = confirm(*c);
    } else {
        ++stats_.unmeasured;
    }
}

double MagneticWindowERD::placePosterior(const Candidate& best, std::vector<Candidate>& all,
                                         std::size_t first,
                                         const magnetic::WindowNullModel& null) const {
    const auto& query = queried().samples();
    // The position prior normalized over the candidates (both directions of every sample).
    double logZ = -INFINITY;
    for (const auto& k : all) {
        const double v = -0.5 * k.gate2;
        logZ = std::max(logZ, v) + std::log1p(std::exp(-std::abs(logZ - v)));
    }
    // A candidate that fits worse than this beyond the fit test weighs nothing next to one
    // that passes it: its likelihood ratio is not worth computing.
    const double negligible =
        magnetic::chiSquareQuantile(3.0 * double(n_), 1 - 1e-12) + best.fit.chi2;
    double maxLog = std::log(params_.nullOdds);
    for (auto& k : all) {
        if (k.fit.chi2 > negligible) continue;
        const auto d = magnetic::windowResiduals(
            query, first, k.track->samples(),
            k.direction == WindowDirection::Forward ? k.sample + 1 - n_ : k.sample, n_, k.direction,
            k.fit);
        k.logWeight = null.logLikelihoodRatio(d) - 0.5 * (k.gate2 + k.fit.turnPriorChi2) - logZ;
        maxLog = std::max(maxLog, k.logWeight);
    }
    const Eigen::Vector2d there = positionAtSample(*best.track, best.sample);
    const int segment = best.track->samples()[best.sample].segment;
    double same = 0, rest = std::exp(std::log(params_.nullOdds) - maxLog);
    for (const auto& k : all) {
        if (!std::isfinite(k.logWeight)) continue;
        const double w = std::exp(k.logWeight - maxLog);
        const bool samePlace =
            k.track->samples()[k.sample].segment == segment &&
            (positionAtSample(*k.track, k.sample) - there).norm() <= params_.distinctRadius;
        (samePlace ? same : rest) += w;
    }
    return same / (same + rest);
}

JsonObject MagneticWindowERD::describe() const {
    JsonObject params;
    params.set("sensor_label", params_.sensorLabel)
        .set("resample_step", params_.step)
        .set("window_length", params_.window)
        .set("query_every", params_.queryEvery)
        .set("window_sigma", params_.noise.sigma)
        .set("window_bias_sigma", params_.noise.biasSigma)
        .set("window_trend_sigma", params_.noise.trendSigma)
        .set("gp_length_scale", params_.lengthScale)
        .set("null_odds", params_.nullOdds)
        .set("min_travel_gap", params_.minTravelGap)
        .set("gate_chi2", params_.gateChi2)
        .set("gate_heading_drift", params_.uncertainty.headingBias)
        .set("gate_floor", params_.uncertainty.floor)
        .set("test_quantile", params_.quantile)
        .set("min_posterior", params_.minPosterior)
        .set("distinct_radius", params_.distinctRadius)
        .set("closure_every", params_.closureEvery)
        .set("confirm", params_.confirm)
        .set("sigma_cross", params_.sigmaCross)
        .set("turn_floor_deg", params_.turnFloorDeg);
    JsonObject stats;
    path_.describeCounts(stats)
        .set("mirror_sensor", mirror_)
        .set("queries", stats_.queries)
        .set("flat", stats_.flat)
        .set("no_candidate", stats_.noCandidate)
        .set("no_fit", stats_.noFit)
        .set("ambiguous", stats_.ambiguous)
        .set("accepted", stats_.accepted)
        .set("unmeasured", stats_.unmeasured)
        .set("confirmed", stats_.confirmed)
        .set("edges", stats_.edges)
        .set("forward_edges", stats_.forward)
        .set("backward_edges", stats_.backward);
    describeQueryTimes(stats, stats_.queryMs);
    JsonObject out;
    out.set("class", getClassName()).set("params", params).set("stats", stats);
    if (truth_) out.set("truth_funnel", describeTruth());
    return out;
}

}  // namespace lodestone::graphslam
