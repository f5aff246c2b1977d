#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/erd/magnetic/MagneticWindowERD.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "../../Stopwatch.h"

namespace lodestone::graphslam {

using magnetic::WindowDirection;

MagneticWindowERD::MagneticWindowERD() {
    setClassName("MagneticWindowERD");
    rebuild();
}

void MagneticWindowERD::rebuild() {
    params_.noise.step = params_.step;
    params_.noise.sigma = prior_sigma_;
    sensors_.clear();
    mirror_.clear();
    poses_.clear();
    n_ = magnetic::SupernodeTrack({params_.step, params_.window, params_.step}, 3)
             .samplesPerSupernode();
    path_ = MagneticPath(params_.uncertainty);
    projected_targets_.clear();
    projected_map_.clear();
    basis_ = std::make_shared<const magnetic::WindowDisplacementModel::Basis>(n_, params_.noise,
                                                                              params_.lengthScale);
    noise_.reset();
    if (params_.learnNoise)
        noise_.emplace(prior_sigma_, params_.noisePriorWindows * 3.0 * double(n_));
    last_learnt_ = -1e18;
    correlated_samples_ = 0;  // the kernel's correlations summed over a window's offsets
    for (int j = 1 - int(n_); j < int(n_); ++j) {
        const double r = j * params_.step / params_.lengthScale;
        correlated_samples_ += std::exp(-0.5 * r * r);
    }
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
    p.chainWindows = s.getInt("chain_windows", p.chainWindows);
    p.learnNoise = s.getBool("learn_noise", p.learnNoise);
    p.noisePriorWindows = s.getDouble("noise_prior_windows", p.noisePriorWindows);
    p.noise.sigma = s.getDouble("window_sigma", p.noise.sigma);
    p.noise.biasSigma = s.getDouble("window_bias_sigma", p.noise.biasSigma);
    p.noise.trendSigma = s.getDouble("window_trend_sigma", p.noise.trendSigma);
    p.lengthScale = s.getDouble("gp_length_scale", p.lengthScale);
    {
        const std::string null = s.getString("null_model", "window");
        using N = Params::NullModel;
        if (null == "window") p.nullModel = N::Window;
        else if (null == "building") p.nullModel = N::Building;
        else s.fail("null_model", "must be window or building (got '" + null + "')");
    }
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
    p.passDisplacement = s.getBool("pass_displacement", p.passDisplacement);
    p.fineAmplitude = s.getBool("fine_amplitude", p.fineAmplitude);
    p.mapThinningRadius = s.getDouble("map_thinning_radius", p.mapThinningRadius);
    p.sigmaAlongFloor = s.getDouble("sigma_along_floor", p.sigmaAlongFloor);
    p.sigmaCross = s.getDouble("sigma_cross", p.sigmaCross);
    p.turnFloorDeg = s.getDouble("turn_floor_deg", p.turnFloorDeg);
    if (!(p.saturation > 0)) s.fail("saturation", "must be > 0");
    if (!(p.step > 0)) s.fail("resample_step", "must be > 0");
    if (!(p.window >= 4 * p.step)) s.fail("window_length", "must be >= 4 x resample_step");
    if (!(p.queryEvery > 0)) s.fail("query_every", "must be > 0");
    if (p.chainWindows < 1 || p.chainWindows > 16) s.fail("chain_windows", "must be 1..16");
    if (!(p.noisePriorWindows > 0)) s.fail("noise_prior_windows", "must be > 0");
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
    if (!(p.mapThinningRadius >= 0)) s.fail("map_thinning_radius", "must be >= 0");
    if (!(p.sigmaAlongFloor > 0) || !(p.sigmaCross > 0) || !(p.turnFloorDeg >= 0))
        s.fail("sigma_cross", "sigmas must be > 0");
    s.finish();
    params_ = p;
    prior_sigma_ = p.noise.sigma;
    rebuild();
}

bool MagneticWindowERD::updateState(mrpt::obs::CActionCollection::Ptr,
                                    mrpt::obs::CSensoryFrame::Ptr, mrpt::obs::CObservation::Ptr) {
    const std::size_t before = stats_.edges;
    for (; seen_ < m_graph->nodes.size() && nodes_ && nodes_->has(seen_); ++seen_) onNode(seen_);
    return stats_.edges > before;
}

void MagneticWindowERD::onNode(TNodeID id) {
    if (id == map_nodes_ && map_nodes_ > 0) {  // the map's nodes are all in
        thinMap();
        projectMapTargets();
    }
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
            if (id < map_nodes_) return;                       // a loaded map's: stored only
            for (const auto& w : windows) {
                const double end = track.samples()[w.last - 1].s;
                if (end - last_query_ + 1e-9 < params_.queryEvery) continue;
                last_query_ = end;
                query(w.first);
            }
        });
}

bool MagneticWindowERD::leftBehind(const magnetic::TrackSample& stored, double queryTravel) const {
    return stored.node < map_nodes_ || stored.s <= queryTravel - params_.minTravelGap;
}

std::optional<double> MagneticWindowERD::intervalFraction(TNodeID k, double s) const {
    if (k == 0 || path_.segment[k - 1] != path_.segment[k] ||
        path_.travel[k] <= path_.travel[k - 1])
        return std::nullopt;
    return std::clamp((s - path_.travel[k - 1]) / (path_.travel[k] - path_.travel[k - 1]), 0.0,
                      1.0);
}

Eigen::Vector2d MagneticWindowERD::positionAtSample(const magnetic::SupernodeTrack& track,
                                                    std::size_t i) const {
    // A sample lies in its node's interval: between node - 1 and node, by travel.
    const auto& sample = track.samples()[i];
    const auto k = static_cast<TNodeID>(sample.node);
    const auto& b = *poses_[k];
    const auto f = intervalFraction(k, sample.s);
    if (!f) return {b.x(), b.y()};
    const auto& a = *poses_[k - 1];
    return {a.x() + *f * (b.x() - a.x()), a.y() + *f * (b.y() - a.y())};
}

double MagneticWindowERD::yawAtSample(const magnetic::SupernodeTrack& track, std::size_t i) const {
    const auto& sample = track.samples()[i];
    const auto k = static_cast<TNodeID>(sample.node);
    const double b = poses_[k]->yaw();
    const auto f = intervalFraction(k, sample.s);
    if (!f) return b;
    const double a = poses_[k - 1]->yaw();
    return a + *f * std::remainder(b - a, 2 * M_PI);
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
            !leftBehind(samples[c + n_ - 1], query[first + n_ - 1].s))
            return;
        start = c;
    }
    Candidate k;
    k.track = &track;
    k.sample = c;
    k.direction = direction;
    k.fit = magnetic::compareWindows(query, first, samples, start, n_, direction, params_.noise,
                                     prior.turn, prior.turnVariance);
    k.position = prior.position;
    k.gate2 = prior.gate2;
    k.total = k.fit.chi2 + prior.gate2;
    k.fitStat = k.fit.chi2;
    out.push_back(k);
}

MagneticWindowERD::Prior MagneticWindowERD::priorAt(const magnetic::SupernodeTrack& track,
                                                    std::size_t c, TNodeID qNode,
                                                    const Eigen::Vector2d& here) const {
    const auto& samples = track.samples();
    Prior p;
    p.position = positionAtSample(track, c);
    // Where the robot can be, and which way it faces, under the pose uncertainty relative to
    // the target. Across a kidnap the graph knows neither: everywhere, any way - until the
    // segment has joined the target's (relocated): then the target is where the solved graph
    // has it (to gate_floor), the robot as uncertain as its path since its last pin.
    const int segment = samples[c].segment, qSegment = path_.segment[qNode];
    if (!sameFrame(segment, qSegment)) return p;
    const auto target = static_cast<TNodeID>(samples[c].node);
    p.gate2 = segment == qSegment
                  ? path_.uncertainty.relativeGateDistance2(target, qNode, here - p.position)
                  : path_.uncertainty.gateDistance2(qNode, here - p.position);
    p.turn = poses_[qNode]->yaw() - poses_[target]->yaw();
    const double turnFloor = params_.turnFloorDeg * M_PI / 180;
    p.turnVariance = path_.uncertainty.covariance(qNode)(2, 2) + turnFloor * turnFloor;
    return p;
}

double MagneticWindowERD::nodeGateBound(const magnetic::TrackSample& sample, TNodeID qNode,
                                        const Eigen::Vector2d& here) const {
    const int segment = sample.segment, qSegment = path_.segment[qNode];
    if (!sameFrame(segment, qSegment)) return 0;  // across a kidnap: everywhere
    const auto k = static_cast<TNodeID>(sample.node);
    const Eigen::Matrix2d S = segment == qSegment
                                  ? path_.uncertainty.relativeGateCovariance(k, qNode)
                                  : path_.uncertainty.gateCovariance(qNode);
    // positionAtSample places the node's samples between node k - 1 and k (at node k when it
    // has no interval).
    const Eigen::Vector2d b(poses_[k]->x(), poses_[k]->y());
    const Eigen::Vector2d a =
        intervalFraction(k, sample.s) ? Eigen::Vector2d(poses_[k - 1]->x(), poses_[k - 1]->y()) : b;
    return closure::PathUncertainty::segmentDistance2(S, a, b, here);
}

void MagneticWindowERD::query(std::size_t first) {
    const auto t0 = Clock::now();
    ++stats_.queries;
    const auto& samples = queried().samples();
    const std::size_t newest = first + n_ - 1;
    const double dof = 3.0 * double(n_);
    Outcome out;
    const double excitation = magnetic::windowExcitation(samples, first, n_, params_.noise.sigma);
    // Flat in either frame is flat: in the robot's the earth's field turns with every turn of
    // the carrier - heading, not place: a rectangle's corners in an even field all look alike.
    // (The map frame's own artefact, the graph's heading through a turn, is weighed down.)
    out.flat = std::min(excitation, mapFrameExcitation(first)) <
               magnetic::chiSquareQuantile(dof - 3, params_.quantile);
    if (out.flat && noiseLearnt() && params_.chainWindows > 1 && params_.passDisplacement)
        out.flat = stretchFlat(first);
    std::vector<Candidate> candidates;
    if (out.flat) {
        ++stats_.flat;  // a flat field matches anywhere
    } else {
        const auto qNode = static_cast<TNodeID>(samples[newest].node);
        const Eigen::Vector2d here = positionAtSample(queried(), newest);
        // Every stored reading the robot left at least min_travel_gap ago, inside the gate:
        // forward on the queried sensor's track, backward on its mirror's.
        // A node's samples lie between it and the node before: a node whose whole interval
        // is outside the gate is passed over without weighing each sample (the margin keeps
        // a bound's rounding from dropping a sample the exact test would keep).
        const double passOver = params_.gateChi2 * (1 + 1e-6) + 1e-9;
        const auto scan = [&](const Sensor& sensor, bool forward, bool backward) {
            const auto& track = *sensor.track;
            const auto& stored = track.samples();
            const auto& redundant = sensor.redundant;
            const auto& nextTarget = sensor.nextTarget;
            for (std::size_t c = 0;
                 c < stored.size() && leftBehind(stored[c], samples[newest].s);) {
                if (c < nextTarget.size() && nextTarget[c] != c) {  // a map's lines walked again
                    c = nextTarget[c];
                    continue;
                }
                std::size_t end = c + 1;  // the node's samples: [c, end)
                while (end < stored.size() && stored[end].node == stored[c].node) ++end;
                if (nodeGateBound(stored[c], qNode, here) > passOver) {
                    c = end;
                    continue;
                }
                for (; c < end && leftBehind(stored[c], samples[newest].s); ++c) {
                    if (c < redundant.size() && redundant[c]) continue;
                    const Prior p = priorAt(track, c, qNode, here);
                    if (p.gate2 > params_.gateChi2) continue;
                    if (forward)
                        compareAt(track, c, WindowDirection::Forward, first, p, candidates);
                    if (backward)
                        compareAt(track, c, WindowDirection::Backward, first, p, candidates);
                }
            }
        };
        const Sensor& own = sensors_.at(params_.sensorLabel);
        if (mirror_.empty()) {
            scan(own, true, true);
        } else {
            scan(own, true, false);
            scan(sensors_.at(mirror_), false, true);
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
    if (candidates.empty()) {
        ++stats_.noCandidate;
        return;
    }
    const double spread = windowSpread(excitation);
    if (params_.passDisplacement) {
        // Each frame adds its own artefact to the field's spread - the robot frame a turn's
        // turning of the earth's field, the map frame the graph's heading errors (a corner's
        // turn spread over the node interval): the smaller is the closer bound.
        const double whole = std::min(spread, mapFrameSpread(first));
        if (params_.fineAmplitude) {
            out.displacement.emplace(basis_, std::min(fineAmplitude(first), whole),
                                     params_.sigmaCross, params_.distinctRadius, whole);
        } else {
            out.displacement.emplace(basis_, whole, params_.sigmaCross, params_.distinctRadius);
        }
        // (building: weighed on the null's footing, its constant taken off once the best fits -
        // the null costs a pass over the path)
        weighDisplaced(candidates, first, *out.displacement,
                       params_.nullModel == Params::NullModel::Building ? 0.0 : NAN);
    }
    const auto likeliest = [&] {
        return *std::min_element(
            candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.total < b.total; });
    };
    out.best = likeliest();
    if (out.best->fitStat > magnetic::chiSquareQuantile(3.0 * double(n_), params_.quantile)) {
        ++stats_.noFit;
        return;
    }
    double firstNull = NAN;  // (null_model = building) the query window's
    if (params_.passDisplacement && params_.nullModel == Params::NullModel::Building) {
        firstNull = weighAgainstBuilding(candidates, first, *out.displacement);
        out.best = likeliest();
    }
    if (!params_.passDisplacement) {
        const magnetic::WindowNullModel null(n_, params_.noise, spread, params_.lengthScale);
        weighSameLine(*out.best, candidates, first, null);
    }
    out.posterior = placePosterior(*out.best, candidates);
    if (out.posterior < params_.minPosterior && params_.passDisplacement &&
        params_.chainWindows > 1 && (!noise_ || noiseLearnt())) {
        // Windows in sequence; then the likeliest place over them, if its own window fits.
        const double fitLimit = magnetic::chiSquareQuantile(3.0 * double(n_), params_.quantile);
        const auto decided = [&] {
            const auto best = std::min_element(
                candidates.begin(), candidates.end(),
                [](const Candidate& a, const Candidate& b) { return a.total < b.total; });
            if (best->fitStat > fitLimit) return false;
            out.best = *best;
            out.posterior = placePosterior(*out.best, candidates);
            return out.posterior >= params_.minPosterior;
        };
        if (chainEvidence(candidates, first, decided, firstNull)) {
            ++stats_.chained;
            if (out.posterior >= params_.minPosterior) ++stats_.chainedAccepted;
        }
    }
    if (out.posterior < params_.minPosterior) {
        ++stats_.ambiguous;
        return;
    }
    ++stats_.accepted;
    if (auto c = measureClosure(*out.best, candidates, first)) {
        out.closed = confirm(*c);
        if (out.closed && noise_) learnNoise(*out.best, first);
    } else {
        ++stats_.unmeasured;
    }
}

}  // namespace lodestone::graphslam
