#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/DeciderRegistry.h>
#include <lodestone/graphslam/SlamEngine.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <algorithm>
#include <stdexcept>

#include "Stopwatch.h"

namespace lodestone::graphslam {

SlamEngine::SlamEngine(std::unique_ptr<NodeDecider> nrd, std::unique_ptr<EdgeDecider> erd,
                       std::unique_ptr<GraphOptimizer> gso,
                       relocalization::Relocalizer::Params relocalization)
    : nrd_(std::move(nrd)),
      erd_(std::move(erd)),
      gso_(std::move(gso)),
      relocalizer_([&] {
          relocalization.spatial = gso_->spatial();  // hypotheses in the graph's own space
          return relocalization;
      }()) {
    graph_.root = 0;
    for (SlamComponent* c :
         std::initializer_list<SlamComponent*>{nrd_.get(), erd_.get(), gso_.get()}) {
        c->setNodeStore(&nodes_);
    }
    nrd_->setGraphPtr(&graph_);
    erd_->setGraphPtr(&graph_);
    gso_->setGraphPtr(&graph_);
    erd_->setSegmentGroups([this](int segment) { return relocalizer_.groupOfSegment(segment); });
    nrd_->keepKeyframeDepth(erd_->wantsKeyframeDepth());
}

std::unique_ptr<SlamEngine> SlamEngine::fromConfig(const mrpt::config::CConfigFileBase& ini) {
    config::IniSection s(ini, "graphslam", config::sourceName(ini));
    const std::string nrdName = s.getString("node_decider", "FusedOdometryNRD");
    const std::string erdName = s.getString("edge_decider", "CompositeERD");
    const std::string gsoName = s.getString("optimizer", "CeresGSO");
    s.finish();
    const auto& reg = DeciderRegistry::instance();
    auto nrd = reg.makeNodeDecider(nrdName, s.where("node_decider"));
    auto erd = reg.makeEdgeDecider(erdName, s.where("edge_decider"));
    auto gso = reg.makeOptimizer(gsoName, s.where("optimizer"));
    nrd->configure(ini);
    erd->configure(ini);
    gso->configure(ini);
    return std::make_unique<SlamEngine>(std::move(nrd), std::move(erd), std::move(gso),
                                        relocalization::Relocalizer::readParams(ini));
}

void SlamEngine::setDiagnosticTruth(const std::shared_ptr<const std::vector<io::TumPose>>& truth) {
    for (SlamComponent* c :
         std::initializer_list<SlamComponent*>{nrd_.get(), erd_.get(), gso_.get()}) {
        c->setDiagnosticTruth(truth);
    }
}

std::set<std::string> SlamEngine::requiredObservations() const {
    std::set<std::string> all = nrd_->requiredObservations();
    for (const auto& o : erd_->requiredObservations()) all.insert(o);
    for (const auto& o : gso_->requiredObservations()) all.insert(o);
    return all;
}

mrpt::poses::CPose3D SlamEngine::currentPose() const {
    return nrd_->getCurrentRobotPosEstimation();
}

void SlamEngine::startInMap(const Graph& graph, std::vector<NodeRecord> records, bool frozen) {
    if (!graph_.nodes.empty() || stats_.observations > 0)
        throw std::logic_error("SlamEngine: a map is loaded before any data");
    if (records.empty() || graph.nodes.size() != records.size())
        throw std::logic_error("SlamEngine: a map's graph and node records disagree");
    graph_.nodes = graph.nodes;
    graph_.edges = graph.edges;
    graph_.root = 0;
    int segments = 0;
    for (TNodeID id = 0; id < records.size(); ++id) {
        segments = std::max(segments, records[id].segment + 1);
        nodes_.add(id, std::move(records[id]));
    }
    map_nodes_ = nodes_.size();
    relocalizer_.adoptMap(graph_, nodes_);
    relocalizer_seen_ = map_nodes_;
    erd_->setMapNodes(map_nodes_);
    nrd_->continueAfterMap(map_nodes_ - 1, segments);
    gso_->adoptMap(map_nodes_);
    if (frozen) gso_->holdFixed(map_nodes_);
}

bool SlamEngine::process(const mrpt::obs::CObservation::Ptr& obs) {
    const auto t0 = Clock::now();
    ++stats_.observations;
    const bool newNode = nrd_->updateState(nullptr, nullptr, obs);
    stats_.nrdSeconds += msSince(t0) / 1e3;
    const auto t1 = Clock::now();
    erd_->updateState(nullptr, nullptr, obs);
    stats_.erdSeconds += msSince(t1) / 1e3;
    afterNodeDecider(newNode);
    const double ms = msSince(t0);
    if (IS_CLASS(*obs, mrpt::obs::CObservation3DRangeScan)) {
        ++stats_.frames;
        stats_.frameMs.push_back(static_cast<float>(ms));
    }
    since_node_ms_ += ms;
    if (newNode) {
        stats_.nodeMs.push_back(static_cast<float>(since_node_ms_));
        since_node_ms_ = 0;
    }
    return newNode;
}

void SlamEngine::afterNodeDecider(bool /*newNode*/) {
    const auto t0 = Clock::now();
    for (; relocalizer_seen_ < nodes_.size(); ++relocalizer_seen_) {
        relocalizer_.addNode(graph_, nodes_, relocalizer_seen_);
        const NodeRecord& record = nodes_.at(relocalizer_seen_);
        if (record.attitude) gso_->addAttitudePrior(relocalizer_seen_, *record.attitude);
        if (record.wheelScale && relocalizer_seen_ > 0)
            gso_->addWheelScaleJacobian(relocalizer_seen_ - 1, relocalizer_seen_,
                                        *record.wheelScale);
    }
    std::vector<LoopClosure> closures;
    for (auto& lc : erd_->takeNewLoopClosures()) {
        proposals_.push_back({lc, !relocalizer_.sameGroup(lc.from, lc.to)});
        if (!proposals_.back().hypothesis) {
            closures.push_back(std::move(lc));
            continue;
        }
        // Joins two parts not yet known to be one map: a hypothesis, not an edge.
        eraseEdge(graph_, lc.from, lc.to, lc.constraint);
        if (const auto merge = relocalizer_.offer(graph_, lc)) applyMerge(*merge);
    }
    if (!closures.empty()) gso_->addLoopClosures(closures);
    gso_->updateState(nullptr, nullptr, nullptr);
    if (!closures.empty()) {
        // What the optimizer kept (it erases what it rejects) is known to every loop closer.
        std::vector<LoopClosure> kept;
        for (auto& lc : closures) {
            if (hasEdge(graph_, lc.from, lc.to, lc.constraint)) kept.push_back(std::move(lc));
        }
        if (!kept.empty()) erd_->closuresKept(kept);
    }
    stats_.gsoSeconds += msSince(t0) / 1e3;
}

void SlamEngine::applyMerge(const relocalization::Relocalizer::Merge& m) {
    // Only the moved group's nodes change; the group it joins (the map) stays where it is.
    const mrpt::poses::CPose3D& T = m.transform;
    std::set<TNodeID> moved;
    for (TNodeID id = 0; id < relocalizer_seen_; ++id) {
        if (relocalizer_.groupOf(id) != m.movedGroup) continue;
        graph_.nodes[id] = T + graph_.nodes.at(id);
        moved.insert(id);
    }
    if (m.keptGroup == 0) ++stats_.relocations;
    for (const auto& lc : m.accepted) graph_.insertEdge(lc.from, lc.to, lc.constraint);
    gso_->addRelocationClosures(m.accepted, moved);
    // Recorded after the moved group was solved against its closures (the map held fixed):
    // the relocated pose is the engine's estimate then, not the rigid move's first guess,
    // which a long segment's own drift can leave off at its far end.
    relocalizer_.commit(m, graph_, nodes_);
}

void SlamEngine::finish() {
    const auto t0 = Clock::now();
    const bool newNode = nrd_->finish();
    stats_.nrdSeconds += msSince(t0) / 1e3;
    const auto t1 = Clock::now();
    erd_->updateState(nullptr, nullptr, nullptr);
    stats_.erdSeconds += msSince(t1) / 1e3;
    afterNodeDecider(newNode);
    const auto t2 = Clock::now();
    gso_->finish();
    stats_.gsoSeconds += msSince(t2) / 1e3;
    if (newNode) stats_.nodeMs.push_back(static_cast<float>(since_node_ms_ + msSince(t0)));
}

JsonObject SlamEngine::describe() const {
    std::size_t closures = 0, rejected = 0;
    for (const auto& lc : gso_->loopClosures()) {
        ++closures;
        rejected += lc.rejected;
    }
    std::size_t keyframes = 0;
    for (const auto& r : nodes_.records()) keyframes += r.keyframe;
    std::map<std::string, int> edgeStats;
    erd_->getEdgesStats(&edgeStats);
    JsonObject perDecider;
    for (const auto& [k, v] : edgeStats) perDecider.set(k, v);
    JsonObject counts;
    counts.set("nodes", graph_.nodes.size())
        .set("edges", graph_.edges.size())
        .set("keyframes", keyframes)
        .set("loop_closures", closures)
        .set("loop_closures_rejected", rejected)
        .set("loop_closures_by_decider", perDecider)
        .set("observations", stats_.observations)
        .set("rgbd_frames", stats_.frames)
        .set("relocations", stats_.relocations);
    if (map_nodes_ > 0) counts.set("map_nodes", map_nodes_);
    JsonObject timing;
    timing.set("node_decider_s", stats_.nrdSeconds)
        .set("edge_decider_s", stats_.erdSeconds)
        .set("optimizer_s", stats_.gsoSeconds);
    return JsonObject()
        .set("counts", counts)
        .set("stage_seconds", timing)
        .set("node_decider", nrd_->describe())
        .set("edge_decider", erd_->describe())
        .set("optimizer", gso_->describe())
        .set("relocalization", relocalizer_.describe());
}

}  // namespace lodestone::graphslam
