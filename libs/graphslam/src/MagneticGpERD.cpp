#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/MagneticGpERD.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "Stopwatch.h"

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
    uncertainty_ = closure::PathUncertainty(params_.uncertainty);
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
    p.edgeEvery = s.getInt("edge_every", p.edgeEvery);
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
    const NodeRecord& rec = nodes_->at(id);
    double step = 0, heading = m_graph->nodes.at(id).yaw();
    double t0 = rec.timestamp;
    const Constraint* odometry = nullptr;
    if (id > 0) {
        const auto e = m_graph->edges.find({id - 1, id});
        // No travel across a kidnap: the edge there says nothing of the path.
        if (e != m_graph->edges.end() && rec.segment == segment_.back()) {
            step = std::hypot(e->second.mean.x(), e->second.mean.y());
            odometry = &e->second;
        }
        t0 = nodes_->at(id - 1).timestamp;
    }
    uncertainty_.addNode(id, odometry, id > 0 ? m_graph->nodes.at(id - 1).yaw() : 0.0);
    const double s0 = travel_.empty() ? 0.0 : travel_.back();
    travel_.push_back(s0 + step);
    segment_.push_back(rec.segment);
    constrained_.push_back(false);
    for (const auto& m : rec.magnetic) {
        if (params_.sensorLabel.empty()) params_.sensorLabel = m.sensorLabel;
        if (m.sensorLabel != params_.sensorLabel) {
            ++stats_.otherSensors;
            continue;
        }
        ++stats_.readings;
        // The field in the robot frame: the sensor's mounting applied.
        const auto& R = m.sensorPose.getRotationMatrix();
        const Eigen::Vector3d inSensor(m.field.x, m.field.y, m.field.z);
        if (!magnetic::usableReading(inSensor, params_.saturation)) {
            ++stats_.droppedReadings;
            continue;
        }
        const Eigen::Vector3d b = R.asEigen() * inSensor;
        const double f = rec.timestamp > t0
                             ? std::clamp((m.timestamp - t0) / (rec.timestamp - t0), 0.0, 1.0)
                             : 1.0;
        for (const auto& sn :
             track_->add(s0 + f * step, magnetic::fieldFeature(b, heading, params_.mode), id,
                         rec.segment)) {
            query(sn);
        }
    }
}

void MagneticGpERD::query(const magnetic::Supernode& q) {
    const auto t0 = Clock::now();
    ++stats_.supernodes;
    const auto& samples = track_->samples();
    const bool follows = previous_supernode_ && *previous_supernode_ + 1 == q.id &&
                         track_->supernodes()[*previous_supernode_].segment == q.segment;
    previous_supernode_ = q.id;
    std::vector<magnetic::SupernodeMatch> matches;
    const TNodeID qNode = static_cast<TNodeID>(samples[q.last - 1].node);
    const double qTravel = samples[q.first].s;
    // Supernodes join the index once the robot is min_travel_gap past them: the nearest ones
    // in field space would otherwise be the query's own overlapping predecessors.
    while (!unindexed_.empty() && samples[track_->supernodes()[unindexed_.front()].last - 1].s <=
                                      qTravel - params_.minTravelGap) {
        index_->add(track_->supernodes()[unindexed_.front()]);
        unindexed_.pop_front();
    }
    if (q.spread < params_.minSpread) {
        ++stats_.flatSupernodes;
    } else {
        const auto here = positionOf(qNode);
        for (const std::size_t id : index_->nearest(q, params_.candidates)) {
            const auto& t = track_->supernodes()[id];
            // Where the robot can be: the two supernodes' ends inside the gate of the pose
            // uncertainty. Across segments the graph's positions are not yet comparable
            // (kidnap): everywhere.
            if (t.segment == q.segment) {
                const auto there = positionOf(static_cast<TNodeID>(samples[t.last - 1].node));
                const Eigen::Vector2d d(here.x - there.x, here.y - there.y);
                if (uncertainty_.gateDistance2(qNode, d) > params_.gateChi2) {
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
        } else if ((best->shift.logLikelihood - runnerUp) /
                       std::max(1.0, best->shift.normalizedRms * best->shift.normalizedRms) <
                   params_.ambiguityLogRatio) {
            // (a fit worse than the GP's noise model - normalized RMS over 1 - makes every
            // likelihood difference less telling: the ratio is deflated by that dispersion)
            ++stats_.ambiguous;
        } else {
            if (places.size() > 1) ++stats_.resolved;
            align(places[bestPlace], *best);
        }
    }
    stats_.queryMs.push_back(msSince(t0));
}

bool MagneticGpERD::nodeAtTravel(double s, int segment, TNodeID& k, double& frac) const {
    const auto it = std::upper_bound(travel_.begin(), travel_.end(), s);
    if (it == travel_.begin() || it == travel_.end()) return false;
    const auto next = static_cast<std::size_t>(it - travel_.begin());
    k = static_cast<TNodeID>(next - 1);
    if (segment_[k] != segment || segment_[next] != segment) return false;
    const double span = travel_[next] - travel_[k];
    frac = span > 0 ? (s - travel_[k]) / span : 0.0;
    return true;
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

std::size_t MagneticGpERD::windowStart(const magnetic::BundleMatch& b) const {
    const auto& sn = track_->supernodes();
    const std::size_t qEnd = sn[b.lastQuery].last;
    const auto window =
        static_cast<std::size_t>(std::lround(params_.gpWindow / params_.track.step));
    return std::max(sn[b.firstQuery].first, qEnd > window ? qEnd - window : 0);
}

std::optional<MagneticGpERD::PathFit> MagneticGpERD::fitAlongPath(const magnetic::BundleMatch& b,
                                                                  std::size_t qBegin) const {
    const auto& samples = track_->samples();
    const auto& sn = track_->supernodes();
    const std::size_t qEnd = sn[b.lastQuery].last;
    const int tSegment = sn[b.lastTarget].segment;
    // Target readings over the query window's travel moved by the offset, plus the scan range.
    const double margin = params_.shift.maxShift + 2 * params_.track.step;
    const double lo = samples[qBegin].s + b.offset - margin,
                 hi = samples[qEnd - 1].s + b.offset + margin;
    const auto first =
        std::lower_bound(samples.begin(), samples.end(), lo,
                         [](const magnetic::TrackSample& a, double v) { return a.s < v; });
    std::vector<double> tx;
    std::vector<Eigen::VectorXf> ty;
    for (auto it = first; it != samples.end() && it->s <= hi; ++it) {
        if (it->segment != tSegment) return std::nullopt;  // the target stretch crosses a kidnap
        tx.push_back(it->s);
        ty.push_back(it->value);
    }
    const double expected = (hi - lo) / params_.track.step;
    if (tx.size() < 0.9 * expected) return std::nullopt;  // a gap in the target's readings
    const int C = track_->channels();
    Eigen::MatrixXd T(static_cast<Eigen::Index>(tx.size()), C);
    for (std::size_t i = 0; i < tx.size(); ++i)
        T.row(static_cast<Eigen::Index>(i)) = ty[i].cast<double>().transpose();
    std::vector<double> qx;
    Eigen::MatrixXd Q(static_cast<Eigen::Index>(qEnd - qBegin), C);
    for (std::size_t i = qBegin; i < qEnd; ++i) {
        qx.push_back(samples[i].s + b.offset);
        Q.row(static_cast<Eigen::Index>(i - qBegin)) = samples[i].value.cast<double>().transpose();
    }
    magnetic::GaussianProcess1D gp(params_.gp);
    gp.fit(tx, T);
    PathFit fit;
    fit.qBegin = qBegin;
    fit.qEnd = qEnd;
    fit.shift = magnetic::scanShift(gp, qx, Q, params_.shift);
    if (!fit.shift.valid) return std::nullopt;
    return fit;
}

void MagneticGpERD::align(const std::vector<magnetic::BundleMatch>& bundles, const PathFit& fit) {
    const magnetic::BundleMatch& b = bundles.front();
    const auto& shift = fit.shift;
    const std::size_t qBegin = fit.qBegin, qEnd = fit.qEnd;
    if (shift.normalizedRms > params_.maxNormalizedRms) {
        ++stats_.gpRejected;
        return;
    }
    ++stats_.alignments;
    Record rec;
    rec.querySupernode = b.lastQuery;
    rec.offset = b.offset;
    rec.shift = shift.shift;
    rec.shiftSigma = shift.sigma;
    rec.normalizedRms = shift.normalizedRms;
    rec.cost = b.meanCost;
    if (params_.alignment == Params::Alignment::Plane) {
        if (!alignInPlane(bundles, qBegin, qEnd, shift.shift, rec)) ++stats_.planeRejected;
    } else {
        addPathEdges(b, qBegin, qEnd, shift, rec);
    }
    if (!rec.edges.empty()) records_.push_back(std::move(rec));
}

void MagneticGpERD::addPathEdges(const magnetic::BundleMatch& b, std::size_t qBegin,
                                 std::size_t qEnd, const magnetic::ShiftResult& shift,
                                 Record& rec) {
    const auto& samples = track_->samples();
    const int tSegment = track_->supernodes()[b.lastTarget].segment;
    // §2.3: the bundle constraint subdivided into node-to-node edges.
    const std::size_t firstNode = samples[qBegin].node, lastNode = samples[qEnd - 1].node;
    const double sigmaAlong2 = shift.sigma * shift.sigma + params_.sigmaAlong * params_.sigmaAlong;
    for (std::size_t qn = firstNode; qn <= lastNode; ++qn) {
        if (constrained_[qn] || qn % static_cast<std::size_t>(params_.edgeEvery) != 0) continue;
        TNodeID k;
        double frac;
        if (!nodeAtTravel(travel_[qn] + b.offset + shift.shift, tSegment, k, frac)) continue;
        const auto e = m_graph->edges.find({k, k + 1});
        if (e == m_graph->edges.end()) continue;
        const auto& d = e->second.mean;
        const mrpt::poses::CPose2D mean(frac * d.x(), frac * d.y(), frac * d.yaw());
        // Along the target's path: the GP's precision; across it and in heading: loose.
        const double len = std::hypot(d.x(), d.y());
        const Eigen::Vector2d u =
            len > 1e-6 ? Eigen::Vector2d(d.x() / len, d.y() / len) : Eigen::Vector2d(1, 0);
        const Eigen::Matrix2d P = u * u.transpose();
        const Eigen::Matrix2d S = sigmaAlong2 * P + params_.sigmaCross * params_.sigmaCross *
                                                        (Eigen::Matrix2d::Identity() - P);
        addEdge(k, qn, mean, S, params_.sigmaYaw * params_.sigmaYaw, rec);
    }
}

void MagneticGpERD::addEdge(TNodeID target, std::size_t queryNode,
                            const mrpt::poses::CPose2D& mean, const Eigen::Matrix2d& positionCov,
                            double yawVariance, Record& rec) {
    mrpt::poses::CPosePDFGaussian z;
    z.mean = mean;
    z.cov.setZero();
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) z.cov(r, c) = positionCov(r, c);
    z.cov(2, 2) = yawVariance;
    const Constraint c = planarConstraint(z);
    const auto q = static_cast<TNodeID>(queryNode);
    // The edges of one alignment are one piece of evidence for the relocalizer.
    registerClosure(target, q, c, records_.size(), false, -rec.normalizedRms);
    // The query node is now known as well as the closure says (in the map frame).
    const double yaw = m_graph->nodes.at(target).yaw();
    const Eigen::Matrix2d R = Eigen::Rotation2Dd(yaw).toRotationMatrix();
    Eigen::Matrix3d pinned = Eigen::Matrix3d::Zero();
    pinned.topLeftCorner<2, 2>() = R * positionCov * R.transpose();
    pinned(2, 2) = yawVariance;
    uncertainty_.pin(q, pinned);
    rec.edges.emplace_back(target, q);
    rec.constraints.push_back(c);
    constrained_[queryNode] = true;
    ++stats_.edges;
}

bool MagneticGpERD::positionAtTravel(double s, int segment, Eigen::Vector2d& p) const {
    TNodeID k;
    double frac;
    if (!nodeAtTravel(s, segment, k, frac)) return false;
    const auto a = positionOf(k), b = positionOf(k + 1);
    p = Eigen::Vector2d(a.x + frac * (b.x - a.x), a.y + frac * (b.y - a.y));
    return true;
}

bool MagneticGpERD::alignInPlane(const std::vector<magnetic::BundleMatch>& bundles,
                                 std::size_t qBegin, std::size_t qEnd, double shift, Record& rec) {
    const auto& samples = track_->samples();
    const auto& sn = track_->supernodes();
    const magnetic::BundleMatch& best = bundles.front();
    const int qSegment = samples[qEnd - 1].segment;
    const int C = track_->channels();
    // The query window where the graph has it now, and where the path alignment puts it.
    std::vector<Eigen::Vector2d> here, there;
    for (std::size_t i = qBegin; i < qEnd; ++i) {
        Eigen::Vector2d a, b;
        if (!positionAtTravel(samples[i].s, qSegment, a) ||
            !positionAtTravel(samples[i].s + best.offset + shift, sn[best.lastTarget].segment, b))
            return false;
        here.push_back(a);
        there.push_back(b);
    }
    const auto m = static_cast<Eigen::Index>(here.size());
    // (dynamic-size on purpose: GCC 12 warns falsely inside umeyama for 2 x N fixed rows)
    Eigen::MatrixXd from(2, m), to(2, m);
    for (Eigen::Index i = 0; i < m; ++i) {
        from.col(i) = here[static_cast<std::size_t>(i)];
        to.col(i) = there[static_cast<std::size_t>(i)];
    }
    const Eigen::Matrix3d T0 = Eigen::umeyama(from, to, false);  // rigid, query -> target
    Eigen::MatrixX2d start(m, 2);
    Eigen::MatrixXd Q(m, C);
    for (Eigen::Index i = 0; i < m; ++i) {
        start.row(i) = (T0.topLeftCorner<2, 2>() * from.col(i) + T0.topRightCorner<2, 1>()).transpose();
        Q.row(i) = samples[qBegin + static_cast<std::size_t>(i)].value.cast<double>().transpose();
    }
    // Every earlier pass the bundles found here: their readings where the graph has them.
    std::vector<Eigen::Vector2d> at;
    std::vector<Eigen::VectorXf> values;
    for (const auto& bb : bundles) {
        const int seg = sn[bb.lastTarget].segment;
        const double lo = samples[qBegin].s + bb.offset - params_.planeMargin,
                     hi = samples[qEnd - 1].s + bb.offset + params_.planeMargin;
        auto it = std::lower_bound(samples.begin(), samples.end(), lo,
                                   [](const magnetic::TrackSample& a, double v) { return a.s < v; });
        for (int k = 0; it != samples.end() && it->s <= hi; ++it, ++k) {
            Eigen::Vector2d p;
            if (k % params_.planeSubsample != 0 || it->segment != seg || !positionAtTravel(it->s, seg, p))
                continue;
            at.push_back(p);
            values.push_back(it->value);
        }
    }
    if (at.size() < static_cast<std::size_t>(m) / 2) return false;
    Eigen::MatrixX2d P(static_cast<Eigen::Index>(at.size()), 2);
    Eigen::MatrixXd Y(static_cast<Eigen::Index>(at.size()), C);
    for (std::size_t i = 0; i < at.size(); ++i) {
        P.row(static_cast<Eigen::Index>(i)) = at[i].transpose();
        Y.row(static_cast<Eigen::Index>(i)) = values[i].cast<double>().transpose();
    }
    magnetic::GaussianProcess2D gp(params_.gp);
    gp.fit(P, Y);
    const auto r = magnetic::alignInPlane(gp, start, Q, params_.plane);
    if (!r.valid || r.normalizedRms > params_.maxNormalizedRms) return false;
    rec.plane = true;
    rec.planeDelta = r.delta;
    rec.normalizedRms = r.normalizedRms;
    // Each query node moved as its readings were: by T0, then by the plane alignment; tied to
    // the target node nearest where the path alignment put it.
    const double yaw0 = std::atan2(T0(1, 0), T0(0, 0));
    Eigen::Matrix2d J90;
    J90 << 0, -1, 1, 0;
    const std::size_t firstNode = samples[qBegin].node, lastNode = samples[qEnd - 1].node;
    for (std::size_t qn = firstNode; qn <= lastNode; ++qn) {
        if (constrained_[qn] || qn % static_cast<std::size_t>(params_.edgeEvery) != 0) continue;
        TNodeID k;
        double frac;
        if (!nodeAtTravel(travel_[qn] + best.offset + shift, sn[best.lastTarget].segment, k, frac))
            continue;
        if (frac > 0.5) ++k;
        const auto& q = m_graph->nodes.at(static_cast<TNodeID>(qn));
        const Eigen::Vector2d moved0 = T0.topLeftCorner<2, 2>() * Eigen::Vector2d(q.x(), q.y()) +
                                       T0.topRightCorner<2, 1>();
        const Eigen::Vector2d moved = r.apply(moved0);
        const mrpt::poses::CPose2D corrected(moved.x(), moved.y(), q.yaw() + yaw0 + r.delta[2]);
        const auto& tk = m_graph->nodes.at(k);
        const mrpt::poses::CPose2D target(tk.x(), tk.y(), tk.yaw());
        // The alignment's covariance at this node (the turn's lever arm included), in k's frame.
        Eigen::Matrix<double, 2, 3> J;
        J << Eigen::Matrix2d::Identity(), J90 * (moved0 - r.pivot);
        const Eigen::Matrix2d S = J * r.covariance * J.transpose() +
                            params_.sigmaAlong * params_.sigmaAlong * Eigen::Matrix2d::Identity();
        const Eigen::Matrix2d Rk = Eigen::Rotation2Dd(tk.yaw()).toRotationMatrix();
        addEdge(k, qn, corrected - target, Rk.transpose() * S * Rk,
                r.covariance(2, 2) + params_.sigmaYaw * params_.sigmaYaw, rec);
    }
    return true;
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
        .set("alignment", params_.alignment == Params::Alignment::Plane ? "plane" : "path");
    double total = 0, worst = 0;
    for (double ms : stats_.queryMs) {
        total += ms;
        worst = std::max(worst, ms);
    }
    JsonObject stats;
    stats.set("readings", stats_.readings)
        .set("dropped_readings", stats_.droppedReadings)
        .set("other_sensor_readings", stats_.otherSensors)
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
        .set("query_ms_mean", stats_.queryMs.empty() ? 0.0 : total / double(stats_.queryMs.size()))
        .set("query_ms_max", worst);
    return JsonObject().set("class", getClassName()).set("params", params).set("stats", stats);
}

}  // namespace lodestone::graphslam
