#include <lodestone/graphslam/SlamEngine.h>
#include <lodestone/graphslam/nrd/KeyframeCloud.h>
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

/** The keyframes' clouds on their nodes' poses now, every n-th point so that at most
 * `maxPoints` are drawn. */
void addKeyframeClouds(const graphslam::SlamEngine& engine, std::size_t maxPoints, ViewCloud& out) {
    const auto& records = engine.nodes().records();
    std::size_t total = 0;
    for (const auto& r : records)
        if (r.cloud) total += r.cloud->points.size();
    if (total == 0 || maxPoints == 0) return;
    const std::size_t stride = (total + maxPoints - 1) / maxPoints;
    std::size_t k = 0;
    for (std::size_t id = 0; id < records.size(); ++id) {
        const auto& cloud = records[id].cloud;
        const auto node = engine.graph().nodes.find(id);
        if (!cloud || node == engine.graph().nodes.end()) continue;
        for (const auto& p : cloud->points) {
            if (k++ % stride != 0) continue;
            double x = 0, y = 0, z = 0;
            node->second.composePoint(p.x, p.y, p.z, x, y, z);
            out.xyz.insert(out.xyz.end(), {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)});
            out.rgb.insert(out.rgb.end(), {p.r, p.g, p.b});
        }
    }
}

}  // namespace

SceneContent snapshotOf(const graphslam::SlamEngine& engine, std::size_t maxPoints) {
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
    // The closures that joined two map groups (relocation merges) are drawn as such.
    std::set<std::pair<std::uint64_t, std::uint64_t>> closures, merges;
    for (const auto& p : engine.proposals())
        if (p.hypothesis) merges.insert({p.closure.from, p.closure.to});
    for (const auto& lc : engine.optimizer().loopClosures()) {
        const bool merge = merges.count({lc.from, lc.to}) > 0;
        c.edges.push_back({lc.from, lc.to, lc.rejected ? EdgeKind::RefusedClosure : EdgeKind::Closure,
                           merge && !lc.rejected ? std::string(kRelocationCloser) : lc.source});
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
    addKeyframeClouds(engine, maxPoints, c.cloud);
    return c;
}

}  // namespace lodestone::view
