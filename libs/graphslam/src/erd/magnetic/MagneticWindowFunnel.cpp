// MagneticWindowERD's diagnostics against the run's true trajectory: for each query that truly
// revisits a place, the stage of the tests the true place reached.
#include <lodestone/graphslam/erd/magnetic/MagneticWindowERD.h>
#include <lodestone/graphslam/erd/magnetic/TruthFunnel.h>

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
    const TruthPositions truth(*truth_, *nodes_, path_, map_nodes_);
    const io::TumPose* q = truth.atNode(qNode);
    const auto qAt = truth.atSample(samples[newest]);
    if (!q || !qAt) return std::nullopt;
    // The true place: the earlier reading truly nearest the query's newest, within
    // distinct_radius.
    const auto place = truth.nearestSample(samples, samples[newest].s - params_.minTravelGap, *qAt,
                                           params_.distinctRadius);
    if (!place) return std::nullopt;  // not a revisit
    TruthQuery r;
    r.queryNode = qNode;
    const std::size_t c = *place;
    const io::TumPose* there = truth.atNode(static_cast<TNodeID>(samples[c].node));
    r.backward = std::abs(std::remainder(q->pose.yaw() - there->pose.yaw(), 2 * M_PI)) > M_PI / 2;
    // Walked back, the place is on the mirror's track: its reading nearest the same travel.
    const auto& track = r.backward ? mirrored() : queried();
    const auto& stored = track.samples();
    if (stored.empty()) return std::nullopt;  // (a mirror that has no reading yet)
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
        const std::size_t start = r.backward ? t : t + 1 - n_;
        const auto direction = r.backward ? WindowDirection::Backward : WindowDirection::Forward;
        const auto fit = magnetic::compareWindows(samples, first, stored, start, n_, direction,
                                                  params_.noise, p.turn, p.turnVariance);
        // (the statistic the fit test takes: with pass_displacement, at distinct_radius apart)
        r.fitChi2 = out.displacement
                        ? out.displacement
                              ->evidence(magnetic::windowResiduals(samples, first, stored, start,
                                                                   n_, direction, fit),
                                         nearRadius(windowTurn(track, start)))
                              .chi2AtRadius
                        : fit.chi2;
    }
    const double fitLimit = magnetic::chiSquareQuantile(3.0 * double(n_), params_.quantile);
    const bool bestHere =
        out.best && out.best->track->samples()[out.best->sample].segment == stored[t].segment &&
        (positionAtSample(*out.best->track, out.best->sample) - positionAtSample(track, t))
                .norm() <= params_.distinctRadius;
    // Where the decision fell near the truth, its tests are the truth's (even when the true
    // sample itself has no whole window); elsewhere, the truth's own window, gate and fit say
    // why it lost.
    using S = TruthStage;
    if (out.flat) {
        r.stage = S::Flat;
    } else if (bestHere) {
        r.stage = !std::isfinite(out.posterior)          ? S::NoFit
                  : out.posterior < params_.minPosterior ? S::Ambiguous
                  : out.closed                           ? S::Closed
                                                         : S::Accepted;
    } else {
        r.stage = !whole                       ? S::NoWindow
                  : p.gate2 > params_.gateChi2 ? S::OutsideGate
                  : r.fitChi2 > fitLimit       ? S::NoFit
                                               : S::LostToOther;
    }
    truth_queries_.push_back(r);
    return truth_queries_.size() - 1;
}

JsonObject MagneticWindowERD::describeTruth() const {
    std::vector<FunnelRecord> records;
    for (const auto& r : truth_queries_)
        records.push_back({r.queryNode, static_cast<int>(r.stage), r.backward, r.gate2, r.fitChi2});
    std::vector<std::string> names;
    for (int k = 0; k <= static_cast<int>(TruthStage::Closed); ++k)
        names.push_back(toString(static_cast<TruthStage>(k)));
    return describeFunnel(records, names, static_cast<int>(TruthStage::OutsideGate),
                          params_.gateChi2);
}

}  // namespace lodestone::graphslam
