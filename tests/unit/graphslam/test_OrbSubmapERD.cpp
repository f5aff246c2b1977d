// OrbSubmapERD on a synthetic feature world: a robot drives two laps of a loop through a room
// whose walls carry features; nodes come from a scripted node decider that hands each keyframe
// the features its camera sees. The second lap must close on the first, with the right pose.
#include "../vision/SyntheticFeatures.h"
#include "ScriptedDeciders.h"

#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/gso/CeresGSO.h>
#include <lodestone/graphslam/erd/CompositeERD.h>
#include <lodestone/graphslam/erd/visual/OrbSubmapERD.h>
#include <lodestone/graphslam/SlamEngine.h>
#include <SyntheticGraph.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationComment.h>

#include <gtest/gtest.h>

using namespace lodestone;

namespace {

struct LoopRun {
    std::unique_ptr<graphslam::SlamEngine> engine;
    const graphslam::OrbSubmapERD* erd{nullptr};
    std::vector<Eigen::Isometry3d> truth;
};

/** Two laps of a 4 m x 4 m square inside the feature room `world`, a node every 0.25 m, every
 * other node a keyframe; odometry with a small heading bias so lap 2 has drifted. */
LoopRun runLoop(const test::FeatureWorld& world) {
    graphslam::SyntheticGraph::Params p;
    p.laps = 2;
    p.side = 4.0;
    p.closureEvery = 0;
    p.odometrySigmaYaw = 0.003;
    auto s = graphslam::SyntheticGraph::make(p);
    LoopRun run;
    std::vector<test::ScriptedNRD::Step> steps;
    std::vector<graphslam::NodeRecord> records;
    for (std::size_t i = 0; i < s.truth.size(); ++i) {
        // The square centred in the room, looking along the path.
        const auto& t = s.truth[i];
        run.truth.push_back(test::planarPose(t.x() - 2, t.y() - 2, t.yaw()));
        graphslam::NodeRecord r;
        r.timestamp = static_cast<double>(i);
        r.keyframe = i % 2 == 0;
        if (r.keyframe) {
            r.features = test::view(world, run.truth.back(), 0.003, 1000 + i);
            r.T_robot_camera = test::forwardCamera();
        }
        records.push_back(r);
        if (i > 0) steps.push_back({s.graph.edges.find({i - 1, i})->second, 0});
    }
    auto erd = std::make_unique<graphslam::OrbSubmapERD>();
    run.erd = erd.get();
    auto composite = std::make_unique<graphslam::CompositeERD>();
    composite->addChild(std::move(erd));
    run.engine = std::make_unique<graphslam::SlamEngine>(
        std::make_unique<test::ScriptedNRD>(steps, records), std::move(composite),
        std::make_unique<graphslam::CeresGSO>());
    const auto tick = mrpt::obs::CObservationComment::Create();
    while (run.engine->process(tick)) {
    }
    run.engine->finish();
    return run;
}

}  // namespace

TEST(OrbSubmapERD, TheSecondLapClosesOnTheFirstWithTheTruePose) {
    const auto world = test::FeatureWorld::room(3000, 11);
    const LoopRun run = runLoop(world);
    const auto& records = run.erd->records();
    ASSERT_GT(records.size(), 5u);
    EXPECT_GT(run.erd->stats().submaps, 3u);
    for (const auto& r : records) {
        const Eigen::Isometry3d truth = run.truth[r.from].inverse() * run.truth[r.to];
        EXPECT_LT((r.relative.translation() - truth.translation()).norm(), 0.03) << r.from << "->" << r.to;
        EXPECT_LT(Eigen::AngleAxisd(r.relative.linear().transpose() * truth.linear()).angle(), 0.02);
        EXPECT_LT(r.from, r.to);
        // Nothing closes on the robot's own recent past.
        EXPECT_GT(r.to - r.from, 10u);
    }
    for (const auto& lc : run.engine->optimizer().loopClosures()) EXPECT_FALSE(lc.rejected);
    // The closures pull lap 2 onto lap 1: its end is back at the start.
    const auto& g = run.engine->graph();
    const auto last = g.nodes.at(g.nodes.size() - 1), first = g.nodes.at(0);
    EXPECT_LT(std::hypot(last.x() - first.x(), last.y() - first.y()), 0.05);
}

TEST(OrbSubmapERD, ARoomItHasNeverSeenGivesNoClosures) {
    // Every keyframe sees fresh random features: no revisit is possible.
    const auto world = test::FeatureWorld::room(3000, 12);
    graphslam::SyntheticGraph::Params p;
    p.laps = 2;
    p.side = 4.0;
    p.closureEvery = 0;
    auto s = graphslam::SyntheticGraph::make(p);
    std::vector<test::ScriptedNRD::Step> steps;
    std::vector<graphslam::NodeRecord> records;
    for (std::size_t i = 0; i < s.truth.size(); ++i) {
        graphslam::NodeRecord r;
        r.keyframe = true;
        const auto other = test::FeatureWorld::room(300, 5000 + i);
        r.features = test::view(other, test::planarPose(0, 0, 0.1 * static_cast<double>(i)), 0.003, i);
        r.T_robot_camera = test::forwardCamera();
        records.push_back(r);
        if (i > 0) steps.push_back({s.graph.edges.find({i - 1, i})->second, 0});
    }
    auto erd = std::make_unique<graphslam::OrbSubmapERD>();
    const auto* erdPtr = erd.get();
    auto composite = std::make_unique<graphslam::CompositeERD>();
    composite->addChild(std::move(erd));
    graphslam::SlamEngine engine(std::make_unique<test::ScriptedNRD>(steps, records), std::move(composite),
                                 std::make_unique<graphslam::CeresGSO>());
    const auto tick = mrpt::obs::CObservationComment::Create();
    while (engine.process(tick)) {
    }
    EXPECT_GT(erdPtr->stats().candidatesTried, 0u);
    EXPECT_EQ(erdPtr->stats().accepted, 0u);
}

TEST(OrbSubmapERD, ConfigurationIsStrict) {
    graphslam::OrbSubmapERD erd;
    mrpt::config::CConfigFileMemory ok("[OrbSubmapERD]\nsubmap_max_keyframes = 1\nmin_votes = 5\n");
    erd.configure(ok);
    EXPECT_EQ(erd.params().submapMaxKeyframes, 1);
    EXPECT_EQ(erd.params().minVotes, 5);
    for (const char* bad : {"[OrbSubmapERD]\nsubmap_max_keyframe = 1\n",
                            "[OrbSubmapERD]\nsubmap_max_keyframes = 0\n",
                            "[OrbSubmapERD]\nphase1_min_inliers = 2\n"}) {
        mrpt::config::CConfigFileMemory ini(bad);
        EXPECT_THROW(erd.configure(ini), config::ConfigError) << bad;
    }
    EXPECT_EQ(erd.params().submapMaxKeyframes, 1);  // a failed read changes nothing
}
