#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/CeresGSO.h>
#include <lodestone/graphslam/SyntheticGraph.h>
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
    for (const char* bad : {"[CeresGSO]\nmode = 2d\n", "[CeresGSO]\nrobust_loss = tukey\n",
                            "[CeresGSO]\nlocal_windw = 3\n", "[CeresGSO]\nlocal_window = 0\n",
                            "[CeresGSO]\nfull_solve_growth = abc\n"}) {
        mrpt::config::CConfigFileMemory ini(bad);
        EXPECT_THROW(gso.configure(ini), lodestone::config::ConfigError) << bad;
    }
}

namespace {
/** A 3-lap graph optimized with all its closures but the last, which is returned. */
LoopClosure optimizedExceptLast(SyntheticGraph& s, Graph& g, CeresGSO& gso) {
    g = s.graph;
    LoopClosure last = s.closures.back();
    s.closures.pop_back();
    for (const auto& lc : s.closures) g.insertEdge(lc.from, lc.to, lc.constraint);
    mrpt::config::CConfigFileMemory ini("[CeresGSO]\nlocal_window = 10\nfull_solve_growth = 100\n");
    gso.configure(ini);
    gso.setGraphPtr(&g);
    gso.addLoopClosures(s.closures);
    gso.optimizeGraph();
    return last;
}
}  // namespace

TEST(CeresGSO, LocalSolvesMoveOnlyNodesNearTheClosure) {
    SyntheticGraph s = SyntheticGraph::make({});
    Graph g;
    CeresGSO gso;
    const LoopClosure lc = optimizedExceptLast(s, g, gso);
    const Graph before = g;
    g.insertEdge(lc.from, lc.to, lc.constraint);
    gso.addLoopClosures({lc});
    EXPECT_TRUE(gso.updateState(nullptr, nullptr, nullptr));
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
    mrpt::config::CConfigFileMemory ini("[CeresGSO]\nlocal_window = 10\nfull_solve_growth = 100\n");
    gso.configure(ini);
    gso.setGraphPtr(&g);
    gso.optimizeGraph();
    const LoopClosure lc = s.closures.back();
    g.insertEdge(lc.from, lc.to, lc.constraint);
    gso.addLoopClosures({lc});
    EXPECT_TRUE(gso.updateState(nullptr, nullptr, nullptr));
    EXPECT_TRUE(gso.justFullyOptimizedGraph());
    EXPECT_EQ(gso.stats().escalations, 1u);
    EXPECT_EQ(gso.stats().rejected, 0u);
}
