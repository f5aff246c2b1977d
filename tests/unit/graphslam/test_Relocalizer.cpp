#include "ScriptedDeciders.h"

#include <lodestone/graphslam/gso/CeresGSO.h>
#include <lodestone/graphslam/erd/CompositeERD.h>
#include <lodestone/graphslam/SlamEngine.h>
#include <SyntheticGraph.h>
#include <lodestone/graphslam/relocalization/Relocalizer.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationComment.h>

#include <gtest/gtest.h>

using namespace lodestone;
using graphslam::Constraint;
using graphslam::LoopClosure;
using graphslam::TNodeID;
using graphslam::relocalization::Relocalizer;

namespace {

constexpr double kStep = 0.25;  // [m] between nodes
constexpr TNodeID kMapNodes = 20;

/** A map (segment 0) driven along x from the origin, then a kidnap: segment 1 drives the same
 * line again from its start, but the graph has it hanging where the map ended (weak edge). */
struct KidnapFixture {
    graphslam::Graph graph;
    graphslam::NodeStore nodes;
    Relocalizer reloc;
    std::vector<mrpt::poses::CPose3D> truth;

    KidnapFixture() {
        Constraint step;
        step.mean = mrpt::poses::CPose3D(kStep, 0, 0, 0, 0, 0);
        step.cov_inv = graphslam::planarInformation(0.01, 0.004);
        for (TNodeID id = 0; id < 2 * kMapNodes; ++id) {
            const bool seg1 = id >= kMapNodes;
            truth.emplace_back(kStep * (seg1 ? id - kMapNodes : id), 0, 0, 0, 0, 0);
            if (id == 0) {
                graph.nodes[0] = mrpt::poses::CPose3D();
            } else if (id == kMapNodes) {
                Constraint weak;
                weak.cov_inv = graphslam::planarInformation(100, 100);
                graph.nodes[id] = graph.nodes.at(id - 1);
                graph.insertEdge(id - 1, id, weak);
            } else {
                graph.nodes[id] = graph.nodes.at(id - 1) + step.mean;
                graph.insertEdge(id - 1, id, step);
            }
            graphslam::NodeRecord r;
            r.timestamp = id;
            r.segment = seg1 ? 1 : 0;
            if (id == kMapNodes) {
                r.liftTime = id - 0.5;
                r.putDownTime = id - 0.1;
            }
            nodes.add(id, r);
            reloc.addNode(graph, nodes, id);
        }
    }

    /** A closure map node -> segment-1 node at the same true place (or `error` off). */
    LoopClosure closure(TNodeID mapNode, TNodeID segNode, double error = 0, bool strong = false,
                        std::string source = "Visual", std::size_t matchId = 0) const {
        LoopClosure lc;
        lc.from = mapNode;
        lc.to = segNode;
        lc.constraint.mean = (truth[segNode] - truth[mapNode]) + mrpt::poses::CPose3D(error, 0, 0, 0, 0, 0);
        lc.constraint.cov_inv = graphslam::planarInformation(0.02, 0.01);
        lc.source = std::move(source);
        lc.matchId = matchId ? matchId : segNode;
        lc.strong = strong;
        return lc;
    }
};

}  // namespace

TEST(Relocalizer, ASingleOrdinaryMatchIsNotEnough) {
    KidnapFixture f;
    EXPECT_EQ(f.reloc.groupOf(kMapNodes + 2), 1);
    EXPECT_FALSE(f.reloc.offer(f.graph, f.closure(2, kMapNodes + 2)));
    // The same match again, or one from the same place, is not independent evidence.
    EXPECT_FALSE(f.reloc.offer(f.graph, f.closure(3, kMapNodes + 3)));
    EXPECT_FALSE(f.reloc.kidnaps().front().relocated);
    EXPECT_EQ(f.reloc.kidnaps().front().hypotheses, 2u);
    EXPECT_EQ(f.reloc.kidnaps().front().liftTime, kMapNodes - 0.5);
}

TEST(Relocalizer, TwoIndependentAgreeingMatchesMoveTheSegmentAndJudgeTheRest) {
    KidnapFixture f;
    EXPECT_FALSE(f.reloc.offer(f.graph, f.closure(2, kMapNodes + 2)));
    // A wrong match 1.5 m off: it disagrees with the first, so nothing is verified ...
    EXPECT_FALSE(f.reloc.offer(f.graph, f.closure(12, kMapNodes + 6, 1.5)));
    // ... until a second right one, 1.5 m further along the segment.
    const auto m = f.reloc.offer(f.graph, f.closure(8, kMapNodes + 8, 0, false, "Magnetic"));
    ASSERT_TRUE(m.has_value());
    EXPECT_EQ(m->keptGroup, 0);
    EXPECT_EQ(m->movedGroup, 1);
    EXPECT_EQ(m->accepted.size(), 2u);
    EXPECT_EQ(m->rejected, 1u);  // the wrong one, judged at the move
    EXPECT_EQ(m->sources, (std::set<std::string>{"Magnetic", "Visual"}));
    // The move puts the segment where it truly is (it hung at the map's end, 4.75 m off).
    for (TNodeID id = kMapNodes; id < 2 * kMapNodes; ++id) {
        const auto moved = m->transform + f.graph.nodes.at(id);
        EXPECT_NEAR(moved.x(), f.truth[id].x(), 1e-6);
        EXPECT_NEAR(moved.y(), f.truth[id].y(), 1e-6);
    }
}

TEST(Relocalizer, AgreeingClosuresThatLeaveTheHeadingFreeWait) {
    // Magnetic-like closures: 0.2 m across, 10 deg in heading, all on one straight line. Two
    // of them 1.5 m apart agree but leave the heading to +-8 deg: no merge yet.
    KidnapFixture f;
    const auto loose = [&](TNodeID mapNode, TNodeID segNode) {
        LoopClosure lc = f.closure(mapNode, segNode, 0, false, "Magnetic");
        lc.constraint.cov_inv = graphslam::planarInformation(0.2, 10 * M_PI / 180);
        return lc;
    };
    EXPECT_FALSE(f.reloc.offer(f.graph, loose(2, kMapNodes + 2)));
    EXPECT_FALSE(f.reloc.offer(f.graph, loose(8, kMapNodes + 8)));
    EXPECT_NE(f.reloc.describe().str().find("\"undetermined_merges\": 1"), std::string::npos);
    // A tight one that agrees pins it down.
    EXPECT_TRUE(f.reloc.offer(f.graph, f.closure(14, kMapNodes + 14)));
}

TEST(Relocalizer, AStrongMatchRelocatesAlone) {
    KidnapFixture f;
    const auto m = f.reloc.offer(f.graph, f.closure(5, kMapNodes + 5, 0, true));
    ASSERT_TRUE(m.has_value());
    EXPECT_EQ(m->accepted.size(), 1u);
}

TEST(Relocalizer, ConfigurationIsStrict) {
    mrpt::config::CConfigFileMemory ini("[relocalization]\nindependent_travel = 2\nmap_sigma_xy = 0.1\n");
    const auto p = Relocalizer::readParams(ini);
    EXPECT_EQ(p.independentTravel, 2.0);
    EXPECT_EQ(p.mapSigmaXY, 0.1);
    mrpt::config::CConfigFileMemory typo("[relocalization]\nindependant_travel = 2\n");
    EXPECT_THROW(Relocalizer::readParams(typo), std::exception);
    mrpt::config::CConfigFileMemory bad("[relocalization]\nmax_hypotheses = 1\n");
    EXPECT_THROW(Relocalizer::readParams(bad), std::exception);
}

// Through the engine: a kidnapped lap relocated by verified closures moves rigidly onto the
// map; the map itself does not move; a wrong single closure never joins them.
TEST(Relocalizer, TheEngineMovesOnlyTheKidnappedSegment) {
    graphslam::SyntheticGraph::Params p;
    p.laps = 2;
    graphslam::SyntheticGraph s = graphslam::SyntheticGraph::make(p);
    const std::size_t k = s.nodesPerLap + s.nodesPerLap / 3;
    std::vector<test::ScriptedNRD::Step> steps;
    for (std::size_t i = 0; i + 1 < s.truth.size(); ++i) {
        steps.push_back({s.graph.edges.find({i, i + 1})->second, i + 1 >= k ? 1 : 0});
    }
    steps[k - 1].edge.mean = mrpt::poses::CPose3D();
    steps[k - 1].edge.cov_inv = graphslam::planarInformation(100, 100);
    std::vector<LoopClosure> closures;
    // A wrong closure first: the segment's first node "seen" 3 m away from where it is.
    LoopClosure wrong;
    wrong.from = 5;
    wrong.to = k + 1;
    wrong.constraint.mean = mrpt::poses::CPose3D(3, 0, 0, 1, 0, 0);
    wrong.constraint.cov_inv = graphslam::planarInformation(0.02, 0.005);
    closures.push_back(wrong);
    for (const auto& lc : s.closures) {
        if (lc.to >= k + 8) closures.push_back(lc);
    }
    auto erd = std::make_unique<graphslam::CompositeERD>();
    erd->addChild(std::make_unique<test::ScriptedLoopCloser>(closures));
    graphslam::SlamEngine engine(std::make_unique<test::ScriptedNRD>(steps), std::move(erd),
                                 std::make_unique<graphslam::CeresGSO>());
    const auto tick = mrpt::obs::CObservationComment::Create();
    std::vector<mrpt::poses::CPose3D> mapBefore;
    std::size_t relocatedAt = 0;
    while (engine.process(tick)) {
        if (!relocatedAt && engine.stats().relocations == 1) {
            relocatedAt = engine.graph().nodes.size();
            for (TNodeID id = 0; id < k; ++id) {
                const auto& a = engine.graph().nodes.at(id);
                const auto& b = mapBefore.at(id);
                EXPECT_LT(std::hypot(a.x() - b.x(), a.y() - b.y()), 1e-3) << "map node " << id;
            }
        }
        if (!relocatedAt) {
            mapBefore.clear();
            for (TNodeID id = 0; id < std::min<std::size_t>(k, engine.graph().nodes.size()); ++id)
                mapBefore.push_back(engine.graph().nodes.at(id));
        }
    }
    engine.finish();
    ASSERT_GT(relocatedAt, 0u);
    const auto& kid = engine.relocalizer().kidnaps();
    ASSERT_EQ(kid.size(), 1u);
    EXPECT_TRUE(kid[0].relocated);
    // Closures begin 2-2.75 m into the segment, one a metre; the second or third verifies
    // (their odometry spacing scatters around independent_travel = 1 m).
    EXPECT_LE(kid[0].travel, 5.0);
    // The wrong closure never became an edge; the segment sits on the truth.
    for (const auto& lc : engine.optimizer().loopClosures()) EXPECT_NE(lc.to, wrong.to);
    EXPECT_EQ(engine.graph().edges.count({wrong.from, wrong.to}), 0u);
    EXPECT_LT(graphslam::positionRmse(engine.graph(), s.truth), 0.15);
}

TEST(Relocalizer, ASegmentMergedAfterItEndedWasNotRelocated) {
    // Segment 1 ends with a second kidnap before any match; segment 2 opens. A later match of
    // segment 1's places still merges it, but the robot was never relocated while in it.
    KidnapFixture f;
    const TNodeID first2 = 2 * kMapNodes;
    Constraint weak;
    weak.cov_inv = graphslam::planarInformation(100, 100);
    for (TNodeID id = first2; id < first2 + 5; ++id) {
        f.graph.nodes[id] = f.graph.nodes.at(id - 1);
        f.graph.insertEdge(id - 1, id, weak);
        graphslam::NodeRecord r;
        r.timestamp = id;
        r.segment = 2;
        f.nodes.add(id, r);
        f.reloc.addNode(f.graph, f.nodes, id);
    }
    EXPECT_FALSE(f.reloc.offer(f.graph, f.closure(2, kMapNodes + 2)));
    const auto m = f.reloc.offer(f.graph, f.closure(8, kMapNodes + 8, 0, false, "Magnetic"));
    ASSERT_TRUE(m.has_value());
    f.reloc.commit(*m, f.graph, f.nodes);
    const auto& k = f.reloc.kidnaps().front();
    EXPECT_FALSE(k.relocated);
    EXPECT_TRUE(k.mergedLate);
    EXPECT_EQ(k.mergeTime, double(first2 + 4));  // the newest node's time: when it was decided
    EXPECT_NE(f.reloc.describe().str().find("\"merged_after_segment_ended\": true"),
              std::string::npos);
}
