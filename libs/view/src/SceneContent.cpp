#include <lodestone/eval/TrajectoryError.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/maps/SavedMap.h>
#include <lodestone/outputs/ClosureTable.h>
#include <lodestone/outputs/NodeTable.h>
#include <lodestone/outputs/RunFiles.h>
#include <lodestone/view/SceneContent.h>

#include "PlyCloud.h"

#include <mrpt/graphs/CNetworkOfPoses.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>

namespace lodestone::view {

const ViewNode* SceneContent::node(std::uint64_t id) const {
    const auto it = std::lower_bound(nodes.begin(), nodes.end(), id,
                                     [](const ViewNode& n, std::uint64_t v) { return n.id < v; });
    return it != nodes.end() && it->id == id ? &*it : nullptr;
}

int SceneContent::segments() const {
    int highest = -1;
    for (const auto& n : nodes) highest = std::max(highest, n.segment);
    return highest + 1;
}

namespace {

/** Each node's error against `truthPath` after the rigid alignment; the truth moved into the
 * estimate's frame for drawing. */
void judge(SceneContent& c, const std::string& truthPath) {
    const auto truth = io::readTumTrajectory(truthPath);
    std::vector<io::TumPose> estimate;
    for (const auto& n : c.nodes) estimate.push_back({n.timestamp, n.pose});
    const eval::AteResult ate = eval::absoluteTrajectoryError(estimate, truth);
    if (ate.pairs == 0)
        throw std::runtime_error(truthPath + ": no pose within 0.02 s of a node's time");
    const Eigen::Isometry3d toTruth = ate.alignment, toEstimate = ate.alignment.inverse();
    c.maxError = 0;
    for (const auto& [e, g] : eval::associate(estimate, truth)) {
        const auto& p = c.nodes[e].pose;
        const auto& q = truth[g].pose;
        const Eigen::Vector3d aligned = toTruth * Eigen::Vector3d(p.x(), p.y(), p.z());
        c.nodes[e].error = (aligned - Eigen::Vector3d(q.x(), q.y(), q.z())).norm();
        c.maxError = std::max(c.maxError, c.nodes[e].error);
    }
    // (the truth at up to 100 poses a second is drawn as a line: one pose in 10 cm is plenty)
    Eigen::Vector3d last = Eigen::Vector3d::Constant(1e300);
    for (const auto& t : truth) {
        const Eigen::Vector3d at = toEstimate * Eigen::Vector3d(t.pose.x(), t.pose.y(), t.pose.z());
        if ((at - last).norm() < 0.1) continue;
        c.truth.emplace_back(at.x(), at.y(), at.z());
        last = at;
    }
}

/** The odometry edges: every graph edge that is not a kept closure. */
void addGraphEdges(SceneContent& c, const graphslam::Graph& graph,
                   const std::set<std::pair<std::uint64_t, std::uint64_t>>& closures) {
    for (const auto& [ends, edge] : graph.edges) {
        (void)edge;
        if (closures.count({ends.first, ends.second})) continue;
        c.edges.push_back({ends.first, ends.second, EdgeKind::Odometry, {}});
    }
}

}  // namespace

SceneContent readRunFolder(const std::string& dir, const RunReadOptions& options) {
    using outputs::RunFile;
    SceneContent c;
    const std::string graphPath = outputs::pathIn(dir, RunFile::Graph);
    if (!std::filesystem::exists(graphPath)) throw std::runtime_error(graphPath + ": not found (not a run's folder?)");
    graphslam::Graph graph;
    try {
        graph.loadFromTextFile(graphPath);
    } catch (const std::exception& e) {
        throw std::runtime_error(graphPath + ": " + e.what());
    }
    const auto rows = outputs::readNodeTable(outputs::pathIn(dir, RunFile::Nodes));
    std::map<std::uint64_t, const outputs::NodeRow*> byId;
    for (const auto& r : rows) byId[static_cast<std::uint64_t>(r.node)] = &r;
    for (const auto& [id, pose] : graph.nodes) {
        ViewNode n;
        n.id = id;
        n.pose = pose;
        const auto it = byId.find(id);
        if (it == byId.end())
            throw std::runtime_error(outputs::pathIn(dir, RunFile::Nodes) + ": no row for node " +
                                     std::to_string(id) + " of " + graphPath);
        n.segment = it->second->segment;
        n.keyframe = it->second->keyframe;
        n.timestamp = it->second->timestamp;
        c.nodes.push_back(n);
    }
    std::set<std::pair<std::uint64_t, std::uint64_t>> kept;
    const std::string closuresPath = outputs::pathIn(dir, RunFile::Closures);
    if (std::filesystem::exists(closuresPath)) {
        for (const auto& r : outputs::readClosureTable(closuresPath)) {
            const auto from = static_cast<std::uint64_t>(r.fromNode), to = static_cast<std::uint64_t>(r.toNode);
            if (!c.node(from) || !c.node(to)) continue;  // (a node the run dropped)
            c.edges.push_back({from, to, r.kept ? EdgeKind::Closure : EdgeKind::RefusedClosure,
                               r.kept && r.hypothesis ? std::string(kRelocationCloser) : r.source});
            if (r.kept) kept.insert({from, to});
        }
    }
    addGraphEdges(c, graph, kept);
    const std::string plyPath = outputs::pathIn(dir, RunFile::Map);
    if (options.maxPoints > 0 && std::filesystem::exists(plyPath))
        c.cloud = readPlyCloud(plyPath, options.maxPoints);
    const std::string meshPath = outputs::pathIn(dir, RunFile::Mesh);
    if (options.maxTriangles > 0 && std::filesystem::exists(meshPath))
        c.mesh = readPlyMesh(meshPath, options.maxTriangles);
    std::string truth = options.groundTruth;
    if (truth.empty() && std::filesystem::exists(outputs::pathIn(dir, RunFile::GroundTruth)))
        truth = outputs::pathIn(dir, RunFile::GroundTruth);
    if (!truth.empty()) judge(c, truth);
    return c;
}

SceneContent fromSavedMap(const maps::SavedMap& map) {
    SceneContent c;
    for (const auto& [id, pose] : map.graph.nodes) {
        ViewNode n;
        n.id = id;
        n.pose = pose;
        if (id < map.nodes.size()) {
            n.segment = map.nodes[id].segment;
            n.keyframe = map.nodes[id].keyframe;
            n.timestamp = map.nodes[id].timestamp;
        }
        c.nodes.push_back(n);
    }
    for (const auto& [ends, edge] : map.graph.edges) {
        (void)edge;
        const ViewNode* a = c.node(ends.first);
        const ViewNode* b = c.node(ends.second);
        const bool chain = a && b && ends.second == ends.first + 1 && a->segment == b->segment;
        c.edges.push_back({ends.first, ends.second, chain ? EdgeKind::Odometry : EdgeKind::Closure,
                           chain ? std::string() : std::string("closure")});
    }
    return c;
}

}  // namespace lodestone::view
