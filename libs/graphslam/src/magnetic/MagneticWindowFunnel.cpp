// MagneticWindowERD's diagnostics against the run's true trajectory: for each query that truly
// revisits a place, the stage of the tests the true place reached.
#include <lodestone/graphslam/magnetic/MagneticWindowERD.h>

#include <algorithm>
#include <cmath>

namespace lodestone::graphslam {

using magnetic::WindowDirection;

const char* MagneticWindowERD::toString(TruthStage stage) {
    switch (stage) {
        case TruthStage::Flat:
            return "flat";
        case TruthStage::NoWindow:
            return "no_window";
        case TruthStage::OutsideGate:
            return "outside_gate";
        case TruthStage::NoFit:
            return "no_fit";
        case TruthStage::LostToOther:
            return "lost_to_other";
        case TruthStage::Ambiguous:
            return "ambiguous";
        case TruthStage::Accepted:
            return "accepted";
        case TruthStage::Closed:
            return "closed";
    }
    return "?";
}

std::optional<std::size_t> MagneticWindowERD::diagnose(std::size_t first, const Outcome& out) {
    const auto& samples = queried().samples();
    const std::size_t newest = first + n_ - 1;
    const auto qNode = static_cast<TNodeID>(samples[newest].node);
    // The true pose of each node (the truth's sample nearest its time, within 0.1 s), and of
    // each reading between its node and the previous one, by travel (as positionAtSample).
    const auto trueAt = [&](TNodeID id) {
        return io::poseNearest(*truth_, nodes_->at(id).timestamp, 0.1);
    };
    const auto trueAtSample = [&](std::size_t i) -> std::optional<Eigen::Vector2d> {
        const auto k = static_cast<TNodeID>(samples[i].node);
        const io::TumPose* b = trueAt(k);
        if (!b) return std::nullopt;
        const Eigen::Vector2d pb(b->pose.x(), b->pose.y());
        const io::TumPose* a = k > 0 ? trueAt(k - 1) : nullptr;
        const double span = k > 0 ? path_.travel[k] - path_.travel[k - 1] : 0;
        if (!a || path_.segment[k - 1] != path_.segment[k] || span <= 0) return pb;
        const double f = std::clamp((samples[i].s - path_.travel[k - 1]) / span, 0.0, 1.0);
        return Eigen::Vector2d(a->pose.x(), a->pose.y()) * (1 - f) + pb * f;
    };
    const io::TumPose* q = trueAt(qNode);
    const auto qAt = trueAtSample(newest);
    if (!q || !qAt) return std::nullopt;
    // The true place: the earlier reading truly nearest the query's newest, within
    // distinct_radius.
    std::optional<std::size_t> place;
    double nearest = params_.distinctRadius;
    for (std::size_t c = 0;
         c < samples.size() && samples[c].s <= samples[newest].s - params_.minTravelGap; ++c) {
        const auto t = trueAtSample(c);
        if (!t) continue;
        const double d = (*t - *qAt).norm();
        if (d <= nearest) {
            nearest = d;
            place = c;
        }
    }
    if (!place) return std::nullopt;  // not a revisit
    TruthQuery r;
    r.queryNode = qNode;
    const std::size_t c = *place;
    const io::TumPose* there = trueAt(static_cast<TNodeID>(samples[c].node));
    r.backward = std::abs(std::remainder(q->pose.yaw() - there->pose.yaw(), 2 * M_PI)) > M_PI / 2;
    // Walked back, the place is on the mirror's track: its reading nearest the same travel.
    const auto& track = r.backward ? mirrored() : queried();
    const auto& stored = track.samples();
    const std::size_t t = std::min<std::size_t>(
        stored.size() - 1,
        static_cast<std::size_t>(
            std::lower_bound(stored.begin(), stored.end(), samples[c].s,
                             [](const magnetic::TrackSample& a, double v) { return a.s < v; }) -
            stored.begin()));
    const bool whole =
        r.backward ? t + n_ <= stored.size() && stored[t + n_ - 1].segment == stored[t].segment &&
                         stored[t + n_ - 1].s <= samples[newest].s - params_.minTravelGap
                   : t + 1 >= n_ && stored[t + 1 - n_].segment == stored[t].segment;
    const Prior p = priorAt(track, t, qNode, positionAtSample(queried(), newest));
    r.gate2 = p.gate2;
    if (whole) {
        r.fitChi2 = magnetic::compareWindows(
                        samples, first, stored, r.backward ? t : t + 1 - n_, n_,
                        r.backward ? WindowDirection::Backward : WindowDirection::Forward,
                        params_.noise, p.turn, p.turnVariance)
                        .chi2;
    }
    const double fitLimit = magnetic::chiSquareQuantile(3.0 * double(n_), params_.quantile);
    const bool bestHere =
        out.best && out.best->track->samples()[out.best->sample].segment == stored[t].segment &&
        (positionAtSample(*out.best->track, out.best->sample) - positionAtSample(track, t))
                .norm() <= params_.distinctRadius;
    using S = TruthStage;
    r.stage = out.flat                                   ? S::Flat
              : !whole                                   ? S::NoWindow
              : p.gate2 > params_.gateChi2               ? S::OutsideGate
              : r.fitChi2 > fitLimit                     ? S::NoFit
              : !bestHere                                ? S::LostToOther
              : !(out.posterior >= params_.minPosterior) ? S::Ambiguous
              : out.closed                               ? S::Closed
                                                         : S::Accepted;
    truthQueries_.push_back(r);
    return truthQueries_.size() - 1;
}

JsonObject MagneticWindowERD::describeTruth() const {
    std::vector<double> node, stage, backward, gate2, fit;
    std::size_t counts[8] = {}, inGate = 0, gated = 0;
    for (const auto& r : truthQueries_) {
        node.push_back(double(r.queryNode));
        stage.push_back(double(static_cast<int>(r.stage)));
        backward.push_back(r.backward ? 1 : 0);
        gate2.push_back(r.gate2);
        fit.push_back(r.fitChi2);
        ++counts[static_cast<int>(r.stage)];
        if (r.stage != TruthStage::Flat && r.stage != TruthStage::NoWindow) {
            ++gated;
            inGate += r.gate2 <= params_.gateChi2;
        }
    }
    JsonObject byStage;
    for (int k = 0; k < 8; ++k) byStage.set(toString(static_cast<TruthStage>(k)), counts[k]);
    return JsonObject()
        .set("revisiting_queries", truthQueries_.size())
        .set("by_stage", byStage)
        .set("truth_inside_gate", gated ? double(inGate) / double(gated) : NAN)
        .set("query_node", node)
        .set("stage", stage)
        .set("backward", backward)
        .set("gate2", gate2)
        .set("fit_chi2", fit);
}

}  // namespace lodestone::graphslam
