#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/gso/CeresGSO.h>
#include <lodestone/graphslam/erd/CompositeERD.h>
#include <lodestone/graphslam/nrd/FusedOdometryNRD.h>
#include <lodestone/graphslam/SlamEngine.h>
#include <lodestone/obs/CObservationWheelDrop.h>
#include <lodestone/sim/RobotConfig.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <lodestone/sim/SimulatorSource.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>

#include "ConfigErrorOf.h"

#include <cmath>
#include <map>

using namespace lodestone;

namespace {

constexpr double kSeconds = 12.0;

/** The first seconds of the office scenario at QVGA, simulated once for all tests. */
const std::vector<mrpt::obs::CObservation::Ptr>& officeObservations(sim::Scenario* scenarioOut = nullptr) {
    static sim::Scenario scenario = [] {
        auto sc = sim::Scenario::load(std::string(LODESTONE_CONFIG_INI_DIR) + "/scenarios/office.ini");
        sc.camera.resize(320, 240);
        return sc;
    }();
    static const std::vector<mrpt::obs::CObservation::Ptr> obs = [] {
        std::vector<mrpt::obs::CObservation::Ptr> v;
        sim::SimulatorSource source(scenario, scenario.seed);
        while (auto o = source.next()) {
            if (source.lastTime() > kSeconds) break;
            v.push_back(o);
        }
        return v;
    }();
    if (scenarioOut) *scenarioOut = scenario;
    return obs;
}

std::unique_ptr<graphslam::SlamEngine> odometryEngine(const sim::Scenario& sc) {
    auto nrd = std::make_unique<graphslam::FusedOdometryNRD>();
    // The simulated robot's wheels, through the decider's own INI keys.
    const mrpt::config::CConfigFileMemory empty;
    nrd->configure(sim::withScenarioWheels(empty, sc, "test"));
    return std::make_unique<graphslam::SlamEngine>(std::move(nrd),
                                                   std::make_unique<graphslam::CompositeERD>(),
                                                   std::make_unique<graphslam::CeresGSO>());
}

}  // namespace

TEST(FusedOdometryNRD, NodesSitOnTheFusedOdometryAtTheirTimes) {
    sim::Scenario sc;
    const auto& obs = officeObservations(&sc);
    auto engine = odometryEngine(sc);
    // The odometry alone, same parameters, same data.
    auto params = dynamic_cast<graphslam::FusedOdometryNRD&>(engine->nodeDecider()).params().odometry;
    odometry::FusedOdometry odo(params);
    std::map<double, mrpt::poses::CPose2D> fused;
    for (const auto& o : obs) {
        engine->process(o);
        for (const auto& e : odo.process(o)) fused[e.timestamp] = e.poses.front().mean;
    }
    engine->finish();
    for (const auto& e : odo.flush()) fused[e.timestamp] = e.poses.front().mean;

    const auto& nodes = engine->nodes();
    ASSERT_GT(nodes.size(), 20u);
    ASSERT_EQ(nodes.size(), engine->graph().nodes.size());
    EXPECT_EQ(engine->graph().edges.size(), nodes.size() - 1);
    const double t0 = fused.begin()->first;
    const auto& origin = fused.begin()->second;
    std::size_t keyframes = 0;
    for (graphslam::TNodeID id = 0; id < nodes.size(); ++id) {
        const auto& rec = nodes.at(id);
        ASSERT_TRUE(fused.count(rec.timestamp)) << "node " << id << " at a time no frame has";
        const auto expected = fused.at(rec.timestamp) - origin;
        const auto& got = engine->graph().nodes.at(id);
        EXPECT_NEAR(got.x(), expected.x(), 1e-6) << id;
        EXPECT_NEAR(got.y(), expected.y(), 1e-6) << id;
        EXPECT_NEAR(std::remainder(got.yaw() - expected.phi(), 2 * M_PI), 0, 1e-6) << id;
        if (rec.keyframe) {
            ++keyframes;
            ASSERT_TRUE(rec.cloud);
            EXPECT_GT(rec.cloud->points.size(), 100u);
            ASSERT_TRUE(rec.features);
            EXPECT_GT(rec.features->size(), 50u);
            // The camera looks forward from above the base: optical z along robot x.
            EXPECT_NEAR(rec.T_robot_camera.linear()(0, 2), 1.0, 1e-6);
        } else {
            EXPECT_FALSE(rec.cloud);
            EXPECT_FALSE(rec.features);
        }
        // Every edge the wheels measured says how it moves with their scales: along by at
        // most half a wheel's travel (the edge's length and half the wheel base's arc), its
        // heading by at most a wheel's travel over the base (less where VO shares the motion).
        EXPECT_EQ(rec.wheelScale.has_value(), id > 0) << id;
        if (id > 0 && rec.wheelScale) {
            const auto d = got - engine->graph().nodes.at(id - 1);
            const double wheelTravel = std::hypot(d.x(), d.y()) + 0.5 * sc.motion.wheelBase *
                                                                   std::abs(d.yaw());
            for (int w = 0; w < 2; ++w) {
                EXPECT_LE(std::abs((*rec.wheelScale)(0, w)), 0.5 * wheelTravel + 2e-3) << id;
                EXPECT_LE(std::abs((*rec.wheelScale)(2, w)),
                          wheelTravel / sc.motion.wheelBase + 0.01)
                    << id;
            }
        }
        // Magnetometer readings: the ones since the previous node, two sensors at 100 Hz.
        if (id > 0) {
            const double from = nodes.at(id - 1).timestamp;
            for (const auto& m : rec.magnetic) {
                EXPECT_GE(m.timestamp, from);  // a reading at a node's very time may come after it
                EXPECT_LE(m.timestamp, rec.timestamp);
            }
            EXPECT_NEAR(static_cast<double>(rec.magnetic.size()), 200 * (rec.timestamp - from), 4.0) << id;
        }
        // Node spacing: the set distance or angle (the last node may be short).
        if (id > 0 && id + 1 < nodes.size()) {
            const auto d = got - engine->graph().nodes.at(id - 1);
            EXPECT_TRUE(std::hypot(d.x(), d.y()) >= 0.10 - 1e-9 ||
                        std::abs(d.yaw()) >= 10 * M_PI / 180 - 1e-9)
                << id;
        }
    }
    EXPECT_GE(nodes.at(0).timestamp, t0);
    EXPECT_GT(keyframes, 2u);
    EXPECT_LT(keyframes, nodes.size() / 2);
}

TEST(FusedOdometryNRD, AKidnapStartsASegmentOnAWeakEdge) {
    sim::Scenario sc;
    const auto& obs = officeObservations(&sc);
    auto engine = odometryEngine(sc);
    const double start = mrpt::Clock::toDouble(obs.front()->timestamp);
    const double lift = start + 4.0, putDown = start + 6.0;
    bool lifted = false, down = false;
    for (const auto& o : obs) {
        const double t = mrpt::Clock::toDouble(o->timestamp);
        if (!lifted && t >= lift) {
            auto drop = obs::CObservationWheelDrop::Create();
            drop->leftDropped = drop->rightDropped = true;
            drop->timestamp = o->timestamp;
            engine->process(drop);
            lifted = true;
        }
        if (!down && t >= putDown) {
            auto drop = obs::CObservationWheelDrop::Create();
            drop->timestamp = o->timestamp;
            engine->process(drop);
            down = true;
        }
        engine->process(o);
    }
    engine->finish();
    const auto& nodes = engine->nodes();
    graphslam::TNodeID firstOfSegment = 0;
    for (graphslam::TNodeID id = 0; id < nodes.size(); ++id) {
        const double t = nodes.at(id).timestamp;
        EXPECT_FALSE(t > lift + 0.05 && t < putDown) << "node " << id << " while lifted";
        for (const auto& m : nodes.at(id).magnetic) {
            EXPECT_FALSE(m.timestamp >= lift && m.timestamp < putDown) << "reading while carried";
        }
        if (!firstOfSegment && nodes.at(id).segment == 1) firstOfSegment = id;
    }
    ASSERT_GT(firstOfSegment, 0u);
    EXPECT_GE(nodes.at(firstOfSegment).timestamp, putDown);
    EXPECT_TRUE(nodes.at(firstOfSegment).keyframe);
    EXPECT_EQ(nodes.at(nodes.size() - 1).segment, 1);
    const auto& across = engine->graph().edges.find({firstOfSegment - 1, firstOfSegment})->second;
    EXPECT_NEAR(across.cov_inv(0, 0), 1e-4, 1e-12);
    EXPECT_NEAR(across.cov_inv(3, 3), 1e-4, 1e-12);
    EXPECT_FALSE(nodes.at(firstOfSegment).wheelScale) << "no wheel measured the carry";
    EXPECT_TRUE(nodes.at(firstOfSegment - 1).wheelScale);
    // The edge before it is ordinary odometry: confident.
    const auto& before = engine->graph().edges.find({firstOfSegment - 2, firstOfSegment - 1})->second;
    EXPECT_GT(before.cov_inv(0, 0), 1e2);
}

TEST(FusedOdometryNRD, ConfigurationMistakesNameTheKey) {
    graphslam::FusedOdometryNRD nrd;
    const auto errorOf = [&](const std::string& text) { return test::configErrorOf(nrd, text); };
    EXPECT_NE(errorOf("[FusedOdometryNRD]\nnode_distanse = 0.2\n").find("node_distanse"),
              std::string::npos);
    EXPECT_NE(errorOf("[FusedOdometryNRD]\nkeyframe_distance = 0.05\n").find("keyframe_distance"),
              std::string::npos);
    EXPECT_NE(errorOf("[odometry_fusion]\nmethod = magic\n").find("method"), std::string::npos);
    EXPECT_EQ(errorOf("[FusedOdometryNRD]\nnode_distance = 0.2\n"), "no error");
    EXPECT_DOUBLE_EQ(nrd.params().nodeDistance, 0.2);
}

namespace {
/** A loop closer that aligns keyframes' depth and leaves the records as they are. */
class DepthWantingCloser : public graphslam::EdgeDecider {
  public:
    void configure(const mrpt::config::CConfigFileBase&) override {}
    graphslam::JsonObject describe() const override { return {}; }
    bool updateState(mrpt::obs::CActionCollection::Ptr, mrpt::obs::CSensoryFrame::Ptr,
                     mrpt::obs::CObservation::Ptr) override {
        return false;
    }
    bool wantsKeyframeDepth() const override { return true; }
};
}  // namespace

TEST(FusedOdometryNRD, KeyframesCarryTheirDepthCloudOnlyWhenALoopCloserAsks) {
    sim::Scenario sc;
    const auto& obs = officeObservations(&sc);
    for (const bool asked : {false, true}) {
        auto nrd = std::make_unique<graphslam::FusedOdometryNRD>();
        const mrpt::config::CConfigFileMemory empty;
        nrd->configure(sim::withScenarioWheels(empty, sc, "test"));
        auto closers = std::make_unique<graphslam::CompositeERD>();
        if (asked) closers->addChild(std::make_unique<DepthWantingCloser>());
        graphslam::SlamEngine engine(std::move(nrd), std::move(closers),
                                     std::make_unique<graphslam::CeresGSO>());
        for (const auto& o : obs) engine.process(o);
        engine.finish();
        std::size_t withDepth = 0;
        for (graphslam::TNodeID id = 0; id < engine.nodes().size(); ++id) {
            const auto& rec = engine.nodes().at(id);
            EXPECT_TRUE(!rec.depth || rec.keyframe) << id;
            if (!rec.depth) continue;
            ++withDepth;
            EXPECT_GT(rec.depth->size(), 500u) << id;  // (QVGA, VO's 80-column grid)
            EXPECT_EQ(rec.depth->normals.cols(), rec.depth->points.cols());
        }
        EXPECT_EQ(withDepth > 0, asked);
    }
}
