// Full solves off the frame loop: a solve of a snapshot merged later gives exactly
// what the same solve in the frame loop gives (nodes added since carried along rigidly, its
// rejections applied), and the engine with background solves is deterministic and as accurate.
#include "ScriptedDeciders.h"

#include <lodestone/graphslam/gso/BackgroundSolve.h>
#include <lodestone/graphslam/gso/CeresGSO.h>
#include <lodestone/graphslam/erd/CompositeERD.h>
#include <lodestone/graphslam/SlamEngine.h>
#include <SyntheticGraph.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationComment.h>

#include <gtest/gtest.h>

using namespace lodestone;
using graphslam::Graph;
using graphslam::LoopClosure;
using graphslam::SyntheticGraph;
using graphslam::TNodeID;

namespace {

/** The first `n` nodes of `s` with their odometry edges and the closures among them (one of
 * them made 3 m wrong, for the solve to reject), closure edges inserted. */
std::pair<Graph, std::vector<LoopClosure>> prefix(const SyntheticGraph& s, TNodeID n) {
    Graph g;
    g.root = 0;
    for (TNodeID id = 0; id < n; ++id) g.nodes[id] = s.graph.nodes.at(id);
    for (const auto& [ends, c] : s.graph.edges) {
        if (ends.second < n) g.insertEdge(ends.first, ends.second, c);
    }
    std::vector<LoopClosure> closures;
    for (const auto& lc : s.closures) {
        if (std::max(lc.from, lc.to) < n) closures.push_back(lc);
    }
    closures.at(closures.size() / 2).constraint.mean += mrpt::poses::CPose3D(3, 0, 0, 0, 0, 0);
    for (const auto& lc : closures) g.insertEdge(lc.from, lc.to, lc.constraint);
    return {g, closures};
}

/** Appends nodes n..m-1 by dead reckoning along `s`'s odometry. */
void extend(Graph& g, const SyntheticGraph& s, TNodeID n, TNodeID m) {
    for (TNodeID id = n; id < m; ++id) {
        const auto& c = s.graph.edges.find({id - 1, id})->second;
        g.nodes[id] = g.nodes.at(id - 1) + c.mean;
        g.insertEdge(id - 1, id, c);
    }
}
}  // namespace

TEST(BackgroundSolve, MergedLaterItIsTheSameSolveAndCarriesNewNodesAlong) {
    const SyntheticGraph s = SyntheticGraph::make({});
    const TNodeID n = static_cast<TNodeID>(2 * s.nodesPerLap), m = n + 40;
    graphslam::PoseGraphSolver::Options options;

    // In the frame loop: solve at n nodes, then 40 more by odometry.
    auto [inLoop, inLoopClosures] = prefix(s, n);
    graphslam::PoseGraphSolver(options).solve(inLoop, inLoopClosures);
    extend(inLoop, s, n, m);

    // In the background: snapshot at n, 40 nodes added meanwhile, merged at m.
    auto [live, liveClosures] = prefix(s, n);
    graphslam::BackgroundSolve background(options, live, liveClosures, m);
    extend(live, s, n, m);
    const auto report = background.mergeInto(live, liveClosures);
    EXPECT_EQ(report.rejected.size(), 1u);

    ASSERT_EQ(live.nodes.size(), inLoop.nodes.size());
    for (const auto& [id, pose] : inLoop.nodes) {
        const auto& got = live.nodes.at(id);
        EXPECT_NEAR(got.x(), pose.x(), 1e-9) << id;
        EXPECT_NEAR(got.y(), pose.y(), 1e-9) << id;
        EXPECT_NEAR(got.yaw(), pose.yaw(), 1e-9) << id;
    }
    // The wrong closure: marked in the live list, its edge gone from the live graph.
    std::size_t rejected = 0;
    for (std::size_t k = 0; k < liveClosures.size(); ++k) {
        EXPECT_EQ(liveClosures[k].rejected, inLoopClosures[k].rejected) << k;
        rejected += liveClosures[k].rejected;
    }
    EXPECT_EQ(rejected, 1u);
    EXPECT_EQ(live.edges.size(), inLoop.edges.size());
}

namespace {
/** Bit for bit the same node poses (the same doubles, not merely close). */
void expectIdentical(const Graph& a, const Graph& b) {
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    for (const auto& [id, pose] : a.nodes) {
        const auto& other = b.nodes.at(id);
        EXPECT_EQ(pose.x(), other.x()) << id;
        EXPECT_EQ(pose.y(), other.y()) << id;
        EXPECT_EQ(pose.yaw(), other.yaw()) << id;
    }
}

Graph runEngine(const SyntheticGraph& s, int backgroundMergeNodes, graphslam::CeresGSO::Stats* stats) {
    std::vector<test::ScriptedNRD::Step> steps;
    for (std::size_t i = 0; i + 1 < s.truth.size(); ++i) {
        steps.push_back({s.graph.edges.find({i, i + 1})->second, 0});
    }
    auto erd = std::make_unique<graphslam::CompositeERD>();
    erd->addChild(std::make_unique<test::ScriptedLoopCloser>(s.closures));
    mrpt::config::CConfigFileMemory ini;
    ini.write("CeresGSO", "background_merge_nodes", backgroundMergeNodes);
    ini.write("CeresGSO", "full_solve_growth", 0.25);  // (several full solves on this small graph)
    auto gso = std::make_unique<graphslam::CeresGSO>();
    gso->configure(ini);
    graphslam::SlamEngine engine(std::make_unique<test::ScriptedNRD>(std::move(steps)),
                                 std::move(erd), std::move(gso));
    const auto tick = mrpt::obs::CObservationComment::Create();
    while (engine.process(tick)) {
    }
    engine.finish();
    if (stats) *stats = dynamic_cast<const graphslam::CeresGSO&>(engine.optimizer()).stats();
    return engine.graph();
}
}  // namespace

TEST(BackgroundSolve, TheEngineWithSolvesOffTheFrameLoopIsDeterministicAndAsAccurate) {
    SyntheticGraph::Params p;
    p.laps = 4;
    const SyntheticGraph s = SyntheticGraph::make(p);
    graphslam::CeresGSO::Stats stats;
    const Graph a = runEngine(s, 15, &stats), b = runEngine(s, 15, nullptr);
    EXPECT_GT(stats.backgroundSolves, 1u);
    expectIdentical(a, b);
    // And so are the frame loop's solves, run after run in one process: local solves once
    // ordered their edges by heap address, which moved the last bits from run to run.
    const Graph inLoop = runEngine(s, 0, nullptr);
    expectIdentical(inLoop, runEngine(s, 0, nullptr));
    const double rmseBackground = graphslam::positionRmse(a, s.truth);
    const double rmseInLoop = graphslam::positionRmse(inLoop, s.truth);
    // The same last full solve: the end result agrees to well under the graph's noise.
    EXPECT_LT(rmseBackground, 0.1);
    EXPECT_NEAR(rmseBackground, rmseInLoop, 0.01);
}
