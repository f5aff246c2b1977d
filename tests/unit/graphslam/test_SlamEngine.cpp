#include "ScriptedDeciders.h"

#include <lodestone/graphslam/gso/CeresGSO.h>
#include <lodestone/graphslam/erd/CompositeERD.h>
#include <lodestone/graphslam/gso/PoseGraphSolver.h>
#include <lodestone/graphslam/SlamEngine.h>
#include <SyntheticGraph.h>
#include <mrpt/obs/CObservationComment.h>

#include <gtest/gtest.h>

using namespace lodestone;
using graphslam::LoopClosure;
using graphslam::SyntheticGraph;

namespace {

std::vector<test::ScriptedNRD::Step> odometryOf(const SyntheticGraph& s) {
    std::vector<test::ScriptedNRD::Step> steps;
    for (std::size_t i = 0; i + 1 < s.truth.size(); ++i) {
        steps.push_back({s.graph.edges.find({i, i + 1})->second, 0});
    }
    return steps;
}

std::unique_ptr<graphslam::SlamEngine> engineFor(std::vector<test::ScriptedNRD::Step> steps,
                                                 std::vector<LoopClosure> closures) {
    auto erd = std::make_unique<graphslam::CompositeERD>();
    erd->addChild(std::make_unique<test::ScriptedLoopCloser>(std::move(closures)));
    return std::make_unique<graphslam::SlamEngine>(
        std::make_unique<test::ScriptedNRD>(std::move(steps)), std::move(erd),
        std::make_unique<graphslam::CeresGSO>());
}

void runAll(graphslam::SlamEngine& engine) {
    const auto tick = mrpt::obs::CObservationComment::Create();
    while (engine.process(tick)) {
    }
    engine.finish();
}

const graphslam::CeresGSO& gsoOf(graphslam::SlamEngine& e) {
    return dynamic_cast<const graphslam::CeresGSO&>(e.optimizer());
}

}  // namespace

TEST(SlamEngine, IncrementalRunEndsAtTheBatchOptimum) {
    SyntheticGraph s = SyntheticGraph::make({});
    const double deadReckoning = graphslam::positionRmse(s.graph, s.truth);
    auto engine = engineFor(odometryOf(s), s.closures);
    runAll(*engine);
    ASSERT_EQ(engine->graph().nodes.size(), s.truth.size());
    EXPECT_EQ(engine->optimizer().loopClosures().size(), s.closures.size());
    const auto& st = gsoOf(*engine).stats();
    EXPECT_GT(st.localSolves, 0u);
    EXPECT_GE(st.fullSolves, 2u);  // at least one on growth, one at the end
    EXPECT_EQ(st.rejected, 0u);

    // The same graph solved at once.
    graphslam::Graph batch = s.graph;
    for (const auto& lc : s.closures) batch.insertEdge(lc.from, lc.to, lc.constraint);
    auto closures = s.closures;
    graphslam::PoseGraphSolver({}).solve(batch, closures);
    double maxDiff = 0;
    for (const auto& [id, p] : batch.nodes) {
        const auto& q = engine->graph().nodes.at(id);
        maxDiff = std::max(maxDiff, std::hypot(p.x() - q.x(), p.y() - q.y()));
    }
    EXPECT_LT(maxDiff, 1e-3);
    EXPECT_LT(graphslam::positionRmse(engine->graph(), s.truth), 0.5 * deadReckoning);
    // MRPT's statistic: the composite reports its child's closures under "lc".
    std::map<std::string, int> stats;
    engine->edgeDecider().getEdgesStats(&stats);
    EXPECT_EQ(stats["lc"], static_cast<int>(s.closures.size()));
    EXPECT_EQ(stats["ScriptedLoopCloser"], static_cast<int>(s.closures.size()));
}

TEST(SlamEngine, AWrongClosureIsRemovedAndReported) {
    SyntheticGraph s = SyntheticGraph::make({});
    LoopClosure wrong = s.closures[s.closures.size() / 3];
    wrong.constraint.mean = wrong.constraint.mean + mrpt::poses::CPose3D(-1.0, 0.7, 0, 0.3, 0, 0);
    s.closures.push_back(wrong);
    auto engine = engineFor(odometryOf(s), s.closures);
    runAll(*engine);
    const auto& closures = engine->optimizer().loopClosures();
    std::size_t rejected = 0;
    for (const auto& lc : closures) {
        if (!lc.rejected) continue;
        ++rejected;
        EXPECT_EQ(lc.to, wrong.to);
        EXPECT_EQ(lc.constraint.mean, wrong.constraint.mean);
        EXPECT_EQ(lc.source, "ScriptedLoopCloser");
    }
    EXPECT_EQ(rejected, 1u);
    const std::string json = engine->describe().str();
    EXPECT_NE(json.find("\"loop_closures_rejected\": 1"), std::string::npos) << json;
    EXPECT_LT(graphslam::positionRmse(engine->graph(), s.truth), 0.15);
}

TEST(SlamEngine, EveryLoopCloserIsToldWhatTheOptimizerKept) {
    // Another closer's closures reach a decider that closes nothing - the right ones, not the
    // one the optimizer refused.
    SyntheticGraph s = SyntheticGraph::make({});
    LoopClosure wrong = s.closures[s.closures.size() / 3];
    wrong.constraint.mean = wrong.constraint.mean + mrpt::poses::CPose3D(-1.0, 0.7, 0, 0.3, 0, 0);
    const std::size_t right = s.closures.size();
    s.closures.push_back(wrong);
    auto erd = std::make_unique<graphslam::CompositeERD>();
    erd->addChild(std::make_unique<test::ScriptedLoopCloser>(s.closures));
    auto recorder = std::make_unique<test::KeptClosureRecorder>();
    const auto* told = recorder.get();
    erd->addChild(std::move(recorder));
    graphslam::SlamEngine engine(std::make_unique<test::ScriptedNRD>(odometryOf(s)), std::move(erd),
                                 std::make_unique<graphslam::CeresGSO>());
    runAll(engine);
    EXPECT_EQ(told->kept.size(), right);
    for (const auto& lc : told->kept) {
        EXPECT_FALSE(lc.constraint.mean == wrong.constraint.mean) << lc.from << " -> " << lc.to;
        EXPECT_EQ(lc.source, "ScriptedLoopCloser");
    }
}

TEST(SlamEngine, AKidnappedSegmentIsReanchoredByItsFirstClosure) {
    SyntheticGraph::Params p;
    p.laps = 2;
    SyntheticGraph s = SyntheticGraph::make(p);
    auto steps = odometryOf(s);
    // Kidnap in the middle of lap 2: the robot is carried from node k-1 to node k; the edge
    // says "somewhere", and lap 2 from there on is segment 1.
    const std::size_t k = s.nodesPerLap + s.nodesPerLap / 3;
    auto& across = steps[k - 1].edge;
    across.mean = mrpt::poses::CPose3D();
    across.cov_inv = graphslam::planarInformation(100, 100);
    for (std::size_t i = k - 1; i < steps.size(); ++i) steps[i].segment = 1;
    // Closures only from segment 1 (nodes >= k) back to lap 1.
    std::vector<LoopClosure> closures;
    for (const auto& lc : s.closures) {
        if (lc.to >= k) closures.push_back(lc);
    }
    ASSERT_GT(closures.size(), 5u);
    auto engine = engineFor(steps, closures);
    runAll(*engine);
    EXPECT_EQ(engine->stats().relocations, 1u);
    EXPECT_EQ(engine->nodes().at(k).segment, 1);
    for (const auto& lc : engine->optimizer().loopClosures()) EXPECT_FALSE(lc.rejected);
    // The optimum of this very graph, found from the true poses: re-anchoring must have led the
    // solver there rather than to the local minimum the weak edge starts it in.
    graphslam::Graph reference = engine->graph();
    for (std::size_t i = 0; i < s.truth.size(); ++i) reference.nodes[i] = s.truth[i];
    auto refClosures = engine->optimizer().loopClosures();
    graphslam::PoseGraphSolver({}).solve(reference, refClosures);
    double worst = 0;
    for (std::size_t i = k; i < s.truth.size(); ++i) {
        const auto& e = engine->graph().nodes.at(i);
        const auto& r = reference.nodes.at(i);
        worst = std::max(worst, std::hypot(e.x() - r.x(), e.y() - r.y()));
    }
    EXPECT_LT(worst, 0.01);
}

TEST(SlamEngine, DecidersWorkThroughMrptsInterfaces) {
    SyntheticGraph s = SyntheticGraph::make({});
    auto engine = engineFor(odometryOf(s), s.closures);
    mrpt::graphslam::deciders::CNodeRegistrationDecider<graphslam::Graph>& nrd = engine->nodeDecider();
    mrpt::graphslam::deciders::CEdgeRegistrationDecider<graphslam::Graph>& erd = engine->edgeDecider();
    mrpt::graphslam::optimizers::CGraphSlamOptimizer<graphslam::Graph>& gso = engine->optimizer();
    EXPECT_TRUE(nrd.updateState(nullptr, nullptr, nullptr));  // root
    EXPECT_TRUE(nrd.updateState(nullptr, nullptr, nullptr));
    EXPECT_EQ(engine->graph().nodes.size(), 2u);
    EXPECT_NEAR(nrd.getCurrentRobotPosEstimation().x(), s.graph.nodes.at(1).x(), 1e-12);
    erd.updateState(nullptr, nullptr, nullptr);
    EXPECT_FALSE(erd.justInsertedLoopClosure());
    engine->optimizer().optimizeGraph();  // protected in MRPT's base, public in ours
    EXPECT_TRUE(gso.justFullyOptimizedGraph());
    EXPECT_EQ(erd.getClassName(), "CompositeERD");
    EXPECT_EQ(gso.getClassName(), "CeresGSO");
}
