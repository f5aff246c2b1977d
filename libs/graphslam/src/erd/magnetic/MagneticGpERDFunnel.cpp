// MagneticGpERD's diagnostics against the run's true trajectory: for each new supernode whose end
// truly revisits a place, the stage the supernode there reached in the sequence matcher.
#include <lodestone/graphslam/erd/magnetic/MagneticGpERD.h>

#include <cmath>
#include <cstdlib>

namespace lodestone::graphslam {

const char* MagneticGpERD::toString(TruthStage stage) {
    switch (stage) {
        case TruthStage::Flat:
            return "flat";
        case TruthStage::Reverse:
            return "reverse";
        case TruthStage::NotShortlisted:
            return "not_shortlisted";
        case TruthStage::OutsideGate:
            return "outside_gate";
        case TruthStage::CostTooHigh:
            return "cost_too_high";
        case TruthStage::NoBundle:
            return "no_bundle";
        case TruthStage::GpRejected:
            return "gp_rejected";
        case TruthStage::Ambiguous:
            return "ambiguous";
        case TruthStage::LostToOther:
            return "lost_to_other";
        case TruthStage::Aligned:
            return "aligned";
    }
    return "?";
}

void MagneticGpERD::diagnose(const magnetic::Supernode& q, const Trace& trace) {
    const auto& samples = track_->samples();
    const auto& supernodes = track_->supernodes();
    const auto qNode = static_cast<TNodeID>(samples[q.last - 1].node);
    const TruthPositions truth(*truth_, *nodes_, path_, map_nodes_);
    const io::TumPose* qPose = truth.atNode(qNode);
    const auto qAt = truth.atSample(samples[q.last - 1]);
    if (!qPose || !qAt) return;
    // The true place: the indexed reading truly nearest the query's end, within 0.5 m (a
    // revisit as lodestone-eval closures counts one); its supernode: the one ending nearest it.
    const auto c =
        truth.nearestSample(samples, samples[q.first].s - params_.minTravelGap, *qAt, 0.5);
    if (!c) return;
    if (supernodes.empty()) return;
    std::size_t t = 0;
    for (std::size_t k = 1; k < supernodes.size() && supernodes[k].last - 1 <= *c + 2; ++k) {
        if (std::labs(long(supernodes[k].last - 1) - long(*c)) <
            std::labs(long(supernodes[t].last - 1) - long(*c)))
            t = k;
    }
    const auto& target = supernodes[t];
    FunnelRecord r;
    r.queryNode = qNode;
    const io::TumPose* there = truth.atNode(static_cast<TNodeID>(samples[*c].node));
    r.backward =
        std::abs(std::remainder(qPose->pose.yaw() - there->pose.yaw(), 2 * M_PI)) > M_PI / 2;
    const auto targetNode = static_cast<TNodeID>(samples[target.last - 1].node);
    const auto here = positionOf(qNode), at = positionOf(targetNode);
    r.gate2 =
        target.segment == q.segment
            ? path_.uncertainty.gateDistance2(qNode, Eigen::Vector2d(here.x - at.x, here.y - at.y))
            : 0.0;
    r.fit = track_->alignedCost(q, target, track_->halfStrideSamples()).first;
    // The truth's place among the bundles' places (the decider's own notion of one place).
    const auto placeOf = [&](const std::vector<magnetic::BundleMatch>& place) {
        const auto p = positionOf(
            static_cast<TNodeID>(samples[supernodes[place.front().lastTarget].last - 1].node));
        return std::hypot(p.x - at.x, p.y - at.y) <= params_.sameplaceRadius;
    };
    std::optional<std::size_t> truthPlace;
    for (std::size_t k = 0; k < trace.places.size(); ++k)
        if (!truthPlace && placeOf(trace.places[k])) truthPlace = k;
    bool shortlisted = false;
    for (const auto id : trace.shortlist) shortlisted |= std::labs(long(id) - long(t)) <= 1;
    using S = TruthStage;
    using O = Trace::Outcome;
    const S stage = trace.flat                             ? S::Flat
                    : r.backward                           ? S::Reverse
                    : !shortlisted                         ? S::NotShortlisted
                    : r.gate2 > params_.gateChi2           ? S::OutsideGate
                    : r.fit > params_.maxCost              ? S::CostTooHigh
                    : !truthPlace                          ? S::NoBundle
                    : trace.outcome == O::GpRejected       ? S::GpRejected
                    : trace.outcome == O::Ambiguous        ? S::Ambiguous
                    : !placeOf(trace.places[trace.chosen]) ? S::LostToOther
                    : trace.edges                          ? S::Aligned
                                                           : S::GpRejected;
    r.stage = static_cast<int>(stage);
    funnel_.push_back(r);
}

}  // namespace lodestone::graphslam
