#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/gso/CeresGSO.h>
#include <ScaledLoop.h>
#include <SyntheticGraph.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>

using namespace lodestone::graphslam;

TEST(CeresGSO, ReadsItsSectionStrictly) {
    CeresGSO gso;
    mrpt::config::CConfigFileMemory se3("[CeresGSO]\nmode = se3\nrobust_loss = huber\n");
    gso.configure(se3);
    EXPECT_FALSE(gso.params().solver.planar);
    EXPECT_NEAR(gso.params().solver.rejectionChi2, 22.46, 0.01);  // 6 degrees of freedom
    EXPECT_EQ(gso.params().solver.robustLoss, "huber");
    EXPECT_EQ(gso.params().wheelScaleSigma, 0.01) << "the wheels' scales: estimated";
    gso.addWheelScaleJacobian(0, 1, Eigen::Matrix<double, 3, 2>::Ones());
    EXPECT_EQ(gso.wheelScale().edges.size(), 1u);
    EXPECT_EQ(gso.wheelScale().sigma, 0.01);
    // Switched off: a wheel-scale Jacobian is not even stored.
    CeresGSO off;
    mrpt::config::CConfigFileMemory unscaled("[CeresGSO]\nwheel_scale_sigma = 0\n");
    off.configure(unscaled);
    off.addWheelScaleJacobian(0, 1, Eigen::Matrix<double, 3, 2>::Ones());
    EXPECT_TRUE(off.wheelScale().edges.empty());
    for (const char* bad : {"[CeresGSO]\nmode = 2d\n", "[CeresGSO]\nrobust_loss = tukey\n",
                            "[CeresGSO]\nlocal_windw = 3\n", "[CeresGSO]\nlocal_window = 0\n",
                            "[CeresGSO]\nfull_solve_growth = abc\n",
                            "[CeresGSO]\nwheel_scale_sigma = -0.01\n"}) {
        mrpt::config::CConfigFileMemory ini(bad);
        EXPECT_THROW(gso.configure(ini), lodestone::config::ConfigError) << bad;
    }
}

namespace {
/** `gso` on `g` with a 10-node window and no growth-triggered full solves, after one full
 * solve of what `g` holds with `closures`. */
void startOn(Graph& g, CeresGSO& gso, const std::vector<LoopClosure>& closures) {
    mrpt::config::CConfigFileMemory ini("[CeresGSO]\nlocal_window = 10\nfull_solve_growth = 100\n");
    gso.configure(ini);
    gso.setGraphPtr(&g);
    gso.addLoopClosures(closures);
    gso.optimizeGraph();
}

/** The synthetic graph with every closure but the last, solved (by a CeresGSO as startOn
 * makes it); the last closure, still to come. */
struct SolvedButLast {
    Graph graph;
    std::vector<LoopClosure> closures;
    LoopClosure last;
};
SolvedButLast solvedButLast() {
    SyntheticGraph s = SyntheticGraph::make({});
    SolvedButLast r{s.graph, s.closures, s.closures.back()};
    r.closures.pop_back();
    for (const auto& c : r.closures) r.graph.insertEdge(c.from, c.to, c.constraint);
    CeresGSO once;
    startOn(r.graph, once, r.closures);
    return r;
}

/** Feeds `lc` as a new closure and lets the optimizer decide how to solve. */
bool addClosure(Graph& g, CeresGSO& gso, const LoopClosure& lc) {
    g.insertEdge(lc.from, lc.to, lc.constraint);
    gso.addLoopClosures({lc});
    return gso.updateState(nullptr, nullptr, nullptr);
}
}  // namespace

TEST(CeresGSO, LocalSolvesMoveOnlyNodesNearTheClosure) {
    // All closures but the last, optimized: the last one is then a small, local correction.
    const SolvedButLast s = solvedButLast();
    const LoopClosure lc = s.last;
    Graph g = s.graph;
    CeresGSO gso;
    startOn(g, gso, s.closures);
    const Graph before = g;
    EXPECT_TRUE(addClosure(g, gso, lc));
    EXPECT_FALSE(gso.justFullyOptimizedGraph());
    EXPECT_EQ(gso.stats().localSolves, 1u);
    EXPECT_EQ(gso.stats().escalations, 0u);
    for (const auto& [id, pose] : g.nodes) {
        const bool near = (id + 10 >= lc.from && id <= lc.from + 10) || (id + 10 >= lc.to && id <= lc.to + 10);
        if (!near) {
            EXPECT_EQ(pose, before.nodes.at(id)) << id;
        }
    }
    EXPECT_NE(g.nodes.at(lc.to), before.nodes.at(lc.to));
    // Nothing new: nothing to do.
    EXPECT_FALSE(gso.updateState(nullptr, nullptr, nullptr));
    gso.finish();
    EXPECT_EQ(gso.stats().fullSolves, 2u);
}

TEST(CeresGSO, AClosureTheWindowCannotAbsorbGoesToAFullSolve) {
    // On the raw dead reckoning the first closure corrects a whole lap of drift: far more than
    // 10 nodes either side can take. The full graph takes it, and keeps it.
    SyntheticGraph s = SyntheticGraph::make({});
    Graph g = s.graph;
    CeresGSO gso;
    startOn(g, gso, {});
    EXPECT_TRUE(addClosure(g, gso, s.closures.back()));
    EXPECT_TRUE(gso.justFullyOptimizedGraph());
    EXPECT_EQ(gso.stats().escalations, 1u);
    EXPECT_EQ(gso.stats().rejected, 0u);
}

TEST(CeresGSO, ALoadedMapCountsAsTheLastFullSolve) {
    // The graph and every closure but the last solved (a map as saved), then the last closure
    // as a run's first: with growth-triggered full solves at every doubling, a fresh optimizer
    // solves the whole graph for it (nothing was solved yet, by its count); one that adopted
    // the map solves around the closure alone.
    const SolvedButLast solved = solvedButLast();
    mrpt::config::CConfigFileMemory ini("[CeresGSO]\nlocal_window = 10\nfull_solve_growth = 1\n");
    for (const bool adopted : {false, true}) {
        Graph g = solved.graph;
        CeresGSO gso;
        gso.configure(ini);
        gso.setGraphPtr(&g);
        if (adopted) gso.adoptMap(static_cast<TNodeID>(g.nodes.size()));
        EXPECT_TRUE(addClosure(g, gso, solved.last));
        EXPECT_EQ(gso.stats().fullSolves, adopted ? 0u : 1u) << adopted;
        EXPECT_EQ(gso.justFullyOptimizedGraph(), !adopted) << adopted;
    }
}

TEST(CeresGSO, AGraphWrittenWithItsWheelScalesKeepsItsShapeWhenSolvedAgain) {
    ScaledLoop s = scaledLoop({0.002, -0.001});
    CeresGSO gso;
    mrpt::config::CConfigFileMemory ini("[CeresGSO]\nwheel_scale_sigma = 0.01\n");
    gso.configure(ini);
    gso.setGraphPtr(&s.graph);
    for (const auto& [ends, jacobian] : s.wheels.edges)
        gso.addWheelScaleJacobian(ends.first, ends.second, jacobian);
    gso.addLoopClosures(s.closures);
    gso.finish();
    ASSERT_LT(worstError(s.graph, s.truth), 0.02);
    // As a map or graph.graph is written (the edges corrected), then solved by a solver that
    // knows nothing of the scales (a map reloaded to extend, MRPT's graph tools): the same
    // shape. Written raw, the same solve bends it back.
    Graph written = s.graph, raw = s.graph;
    gso.calibrateEdges(written);
    std::vector<LoopClosure> closures = s.closures;
    PoseGraphSolver::Options o;
    PoseGraphSolver(o).solve(written, closures, {}, false);
    PoseGraphSolver(o).solve(raw, closures, {}, false);
    EXPECT_LT(worstError(written, s.truth), 0.02);
    EXPECT_GT(worstError(raw, s.truth), 0.1);
    // The closures are not the wheels': left as they were.
    for (const auto& lc : s.closures) {
        EXPECT_EQ(written.edges.find({lc.from, lc.to})->second.mean, lc.constraint.mean);
    }
}
