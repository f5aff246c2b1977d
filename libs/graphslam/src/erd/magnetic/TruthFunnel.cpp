#include <lodestone/graphslam/erd/magnetic/TruthFunnel.h>

#include <algorithm>
#include <cstdint>

namespace lodestone::graphslam {

const io::TumPose* TruthPositions::atNode(TNodeID id) const {
    if (id < first_node_) return nullptr;
    return io::poseNearest(truth_, nodes_.at(id).timestamp, 0.1);
}

std::optional<Eigen::Vector2d> TruthPositions::atSample(const magnetic::TrackSample& sample) const {
    const auto k = static_cast<TNodeID>(sample.node);
    return atSample(sample, atNode(k), k > 0 ? atNode(k - 1) : nullptr);
}

std::optional<Eigen::Vector2d> TruthPositions::atSample(const magnetic::TrackSample& sample,
                                                        const io::TumPose* b,
                                                        const io::TumPose* a) const {
    const auto k = static_cast<TNodeID>(sample.node);
    if (!b) return std::nullopt;
    const Eigen::Vector2d pb(b->pose.x(), b->pose.y());
    const double span = k > 0 ? path_.travel[k] - path_.travel[k - 1] : 0;
    if (!a || path_.segment[k - 1] != path_.segment[k] || span <= 0) return pb;
    const double f = std::clamp((sample.s - path_.travel[k - 1]) / span, 0.0, 1.0);
    return Eigen::Vector2d(a->pose.x(), a->pose.y()) * (1 - f) + pb * f;
}

std::optional<std::size_t> TruthPositions::nearestSample(
    const std::vector<magnetic::TrackSample>& samples, double travelBefore,
    const Eigen::Vector2d& here, double radius) const {
    std::optional<std::size_t> place;
    double nearest = radius;
    // (the truth at a node is looked up once for all its samples: they come in node order)
    std::size_t node = SIZE_MAX;
    const io::TumPose *b = nullptr, *a = nullptr;
    for (std::size_t c = 0; c < samples.size() && samples[c].s <= travelBefore; ++c) {
        if (samples[c].node < first_node_) continue;  // (a map's: no truth here)
        if (samples[c].node != node) {
            node = samples[c].node;
            const auto k = static_cast<TNodeID>(node);
            b = atNode(k);
            a = k > 0 ? atNode(k - 1) : nullptr;
        }
        const auto t = atSample(samples[c], b, a);
        if (!t) continue;
        const double d = (*t - here).norm();
        if (d <= nearest) {
            nearest = d;
            place = c;
        }
    }
    return place;
}

JsonObject describeFunnel(const std::vector<FunnelRecord>& records,
                          const std::vector<std::string>& stageNames, int firstGated,
                          double gateChi2) {
    std::vector<double> node, stage, backward, gate2, fit;
    std::vector<std::size_t> counts(stageNames.size(), 0);
    std::size_t inGate = 0, gated = 0;
    for (const auto& r : records) {
        node.push_back(double(r.queryNode));
        stage.push_back(double(r.stage));
        backward.push_back(r.backward ? 1 : 0);
        gate2.push_back(r.gate2);
        fit.push_back(r.fit);
        ++counts.at(static_cast<std::size_t>(r.stage));
        if (r.stage >= firstGated) {
            ++gated;
            inGate += r.gate2 <= gateChi2;
        }
    }
    JsonObject byStage, names;
    for (std::size_t k = 0; k < stageNames.size(); ++k) {
        byStage.set(stageNames[k], counts[k]);
        names.set(std::to_string(k), stageNames[k]);
    }
    return JsonObject()
        .set("revisiting_queries", records.size())
        .set("stage_names", names)
        .set("by_stage", byStage)
        .set("truth_inside_gate", gated ? double(inGate) / double(gated) : NAN)
        .set("query_node", node)
        .set("stage", stage)
        .set("backward", backward)
        .set("gate2", gate2)
        .set("fit", fit);
}

}  // namespace lodestone::graphslam
