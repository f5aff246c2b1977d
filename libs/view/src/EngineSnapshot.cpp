#include <lodestone/graphslam/SlamEngine.h>
#include <lodestone/view/EngineSnapshot.h>

#include <cmath>
#include <set>

namespace lodestone::view {

namespace {

double meanField(const graphslam::NodeRecord& r) {
    if (r.magnetic.empty()) return NAN;
    double sum = 0;
    for (const auto& m : r.magnetic) sum += m.field.norm();
    return sum / double(r.magnetic.size());
}

}  // namespace

SceneContent snapshotOf(const graphslam::SlamEngine& engine) {
    SceneContent c;
    const auto& graph = engine.graph();
    const auto& store = engine.nodes();
    c.nodes.reserve(graph.nodes.size());
    for (const auto& [id, pose] : graph.nodes) {
        ViewNode n;
        n.id = id;
        n.pose = pose;
        if (store.has(id)) {
            const auto& r = store.at(id);
            n.segment = engine.relocalizer().groupOfSegment(r.segment);
            n.keyframe = r.keyframe;
            n.timestamp = r.timestamp;
            n.field = meanField(r);
        }
        c.nodes.push_back(n);
    }
    std::set<std::pair<std::uint64_t, std::uint64_t>> closures;
    for (const auto& lc : engine.optimizer().loopClosures()) {
        c.edges.push_back({lc.from, lc.to, lc.rejected ? EdgeKind::RefusedClosure : EdgeKind::Closure, lc.source});
        if (!lc.rejected) closures.insert({lc.from, lc.to});
    }
    for (const auto& [ends, edge] : graph.edges) {
        (void)edge;
        if (!closures.count({ends.first, ends.second}))
            c.edges.push_back({ends.first, ends.second, EdgeKind::Odometry, {}});
    }
    if (!graph.nodes.empty()) {
        c.hasCurrent = true;
        c.current = engine.currentPose();
    }
    return c;
}

}  // namespace lodestone::view
