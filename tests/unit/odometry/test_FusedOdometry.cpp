#include <gtest/gtest.h>
#include <lodestone/eval/TrajectoryError.h>
#include <lodestone/odometry/FusedOdometry.h>
#include <lodestone/sim/SimulatorSource.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationOdometry.h>

using namespace lodestone;

namespace {
struct OfficeRun {
    std::vector<std::vector<io::TumPose>> est;
    std::vector<io::TumPose> gt;
    std::size_t tracked{0}, lost{0};
    vision::VoTotals vo;
};

OfficeRun runOffice(const std::string& surface = "") {
    sim::Scenario sc = sim::Scenario::load(std::string(LODESTONE_CONFIG_INI_DIR) + "/scenarios/office.ini");
    sc.camera.resize(320, 240);
    sc.camera.rate = 15;
    if (!surface.empty()) {
        for (auto& w : sc.walls) w.surface = sim::SurfaceSpec::parse(surface);
        sc.floor = sim::SurfaceSpec::parse(surface);
    }
    sim::SimulatorSource source(sc, sc.seed);
    odometry::FusedOdometry::Params p;
    p.wheels.wheelBase = sc.motion.wheelBase;
    p.wheels.wheelRadius = sc.motion.wheelRadius;
    p.wheels.ticksPerRev = sc.encoders.ticksPerRev;
    odometry::FusedOdometry odo(p, {"wheel", "visual", "covariance", "kalman"});
    OfficeRun r;
    r.est.resize(4);
    const auto take = [&](const std::vector<odometry::FusedOdometry::Estimate>& es) {
        for (const auto& e : es) {
            for (std::size_t m = 0; m < 4; ++m) {
                const auto& q = e.poses[m].mean;
                r.est[m].push_back(
                    {e.timestamp, mrpt::poses::CPose3D(q.x(), q.y(), 0, q.phi(), 0, 0)});
            }
            const auto t = source.truePose(e.timestamp - sc.startTime);
            r.gt.push_back({e.timestamp, mrpt::poses::CPose3D(t.x, t.y, 0, t.yaw, 0, 0)});
            r.tracked += e.visual.success;
            r.lost += e.visual.state == vision::VoState::Lost;
        }
    };
    while (auto obs = source.next()) take(odo.process(obs));
    take(odo.flush());
    r.vo = odo.visual().totals();
    return r;
}
}  // namespace

TEST(FusedOdometry, FusionBeatsEitherSourceInATexturedRoom) {
    const OfficeRun r = runOffice();
    ASSERT_GT(r.gt.size(), 400u);  // 28.5 s at 15 Hz
    EXPECT_GT(r.tracked, r.gt.size() * 9 / 10);
    double ate[4];
    for (int m = 0; m < 4; ++m) ate[m] = eval::absoluteTrajectoryError(r.est[m], r.gt).rmse;
    EXPECT_GT(ate[0], 0.03) << "the wheels drift (scale errors and slip)";
    EXPECT_LT(ate[1], 0.05) << "VO tracks the textured room";
    EXPECT_LT(ate[2], ate[0]) << "covariance fusion beats the wheels";
    EXPECT_LT(ate[2], ate[1]) << "covariance fusion beats VO";
    EXPECT_LT(ate[3], ate[0]) << "paper 003's Kalman blend beats the wheels";
    // The wheels' prediction, moved into the camera's optical frame, puts the features where
    // they are: nearly every tracked frame is matched inside its gates.
    EXPECT_GT(r.vo.guided, r.tracked * 9 / 10) << r.vo.guidedFallback << " fell back";
}

TEST(FusedOdometry, InAFeaturelessRoomVoIsLostAndFusionFollowsTheWheels) {
    const OfficeRun r = runOffice("plain");
    EXPECT_GT(r.lost, r.gt.size() * 9 / 10);
    const double wheel = eval::absoluteTrajectoryError(r.est[0], r.gt).rmse;
    for (int m : {2, 3}) {
        EXPECT_NEAR(eval::absoluteTrajectoryError(r.est[m], r.gt).rmse, wheel, 1e-3) << m;
    }
}

TEST(FusedOdometry, ParamsFromIniAndUnknownMethod) {
    mrpt::config::CConfigFileMemory ini(
        "[wheel_odometry]\nwheel_base = 0.3\n[visual_odometry]\norb_features = 400\nlost_after = "
        "3\n"
        "[odometry_fusion]\nmethod = kalman\nkalman_weight = 0.6\n");
    odometry::FusedOdometry::Params p;
    p.loadFromConfigFile(ini, "odometry_fusion");
    EXPECT_DOUBLE_EQ(p.wheels.wheelBase, 0.3);
    EXPECT_EQ(p.visual.orb.features, 400);
    EXPECT_EQ(p.visual.lostAfter, 3);
    EXPECT_EQ(p.method, "kalman");
    EXPECT_DOUBLE_EQ(p.kalmanWeight, 0.6);
    mrpt::config::CConfigFileMemory bad("[odometry_fusion]\nmethod = average\n");
    EXPECT_THROW(p.loadFromConfigFile(bad, "odometry_fusion"), std::runtime_error);
    mrpt::config::CConfigFileMemory typo("[visual_odometry]\norb_feature = 400\n");
    EXPECT_THROW(p.loadFromConfigFile(typo, "odometry_fusion"), std::runtime_error);
}

TEST(FusedOdometry, ShippedIniLoadsWithItsDefaults) {
    mrpt::config::CConfigFile ini(std::string(LODESTONE_CONFIG_INI_DIR) + "/slam/odometry.ini");
    odometry::FusedOdometry::Params p;
    p.loadFromConfigFile(ini, "odometry_fusion");
    const odometry::FusedOdometry::Params defaults;
    EXPECT_EQ(p.method, defaults.method);
    EXPECT_DOUBLE_EQ(p.wheels.wheelBase, defaults.wheels.wheelBase);
    EXPECT_EQ(p.visual.orb.features, defaults.visual.orb.features);
    EXPECT_NEAR(p.visual.maxRotation, defaults.visual.maxRotation, 1e-3);
    EXPECT_NEAR(p.visual.keyframeAngle, defaults.visual.keyframeAngle, 1e-3);
    EXPECT_DOUBLE_EQ(p.visual.ransac.threshold, defaults.visual.ransac.threshold);
    EXPECT_EQ(p.encoderLabel, "");
    EXPECT_DOUBLE_EQ(p.posePositionNoise, defaults.posePositionNoise);
    EXPECT_DOUBLE_EQ(p.poseHeadingNoise, defaults.poseHeadingNoise);
}

TEST(FusedOdometry, PoseOnlyOdometryGivesAnEstimatePerSampleWithTheConfiguredNoise) {
    odometry::FusedOdometry::Params p;
    p.posePositionNoise = 4e-4;
    p.poseHeadingNoise = 1e-4;
    odometry::FusedOdometry odo(p, {"wheel", "covariance"});
    std::vector<odometry::FusedOdometry::Estimate> out;
    for (int k = 0; k < 5; ++k) {
        auto o = mrpt::obs::CObservationOdometry::Create();
        o->timestamp = mrpt::Clock::fromDouble(10.0 + 0.1 * k);
        o->odometry = mrpt::poses::CPose2D(0.1 * k, 0.02 * k * k, 0.1 * k);  // no encoders
        for (auto& e : odo.process(o)) out.push_back(e);
    }
    ASSERT_EQ(out.size(), 5u);
    EXPECT_EQ(odo.poseSamples(), 5u);
    // Both methods report the source as it is: poses relative to the first sample.
    for (std::size_t m = 0; m < 2; ++m) {
        EXPECT_NEAR(out.back().poses[m].mean.x(), 0.4, 1e-12);
        EXPECT_NEAR(out.back().poses[m].mean.y(), 0.32, 1e-12);
        EXPECT_NEAR(out.back().poses[m].mean.phi(), 0.4, 1e-12);
    }
    const auto& inc = out[2].increments[0];
    const auto expected =
        mrpt::poses::CPose2D(0.2, 0.08, 0.2) - mrpt::poses::CPose2D(0.1, 0.02, 0.1);
    EXPECT_NEAR(inc.mean.x(), expected.x(), 1e-12);
    EXPECT_NEAR(inc.mean.phi(), 0.1, 1e-12);
    EXPECT_DOUBLE_EQ(inc.cov(0, 0), 4e-4);
    EXPECT_DOUBLE_EQ(inc.cov(2, 2), 1e-4);
    // Uncertainty grows along the chain.
    EXPECT_GT(out.back().poses[0].cov(1, 1), out[1].poses[0].cov(1, 1));
}
