#include <gtest/gtest.h>
#include <lodestone/sim/RgbdRenderer.h>
#include <lodestone/vision/RgbdVisualOdometry.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "SimTestWorlds.h"
#include "TestPaths.h"
#include "ThreeDMatchFrames.h"

using namespace lodestone::vision;

namespace {
const std::filesystem::path k3dMatch = lodestone::test::threeDMatchDir();

RgbdFrame loadFrame(int index) { return lodestone::test::threeDMatchFrame(index); }
Eigen::Isometry3d loadPose(int index) { return lodestone::test::threeDMatchPose(index); }

// A simulated frame: the box world's posters wall seen from `x` metres along +x.
RgbdFrame simulatedFrame(const lodestone::sim::World& world, const lodestone::sim::CameraSpec& cam,
                         double x, double yaw) {
    lodestone::sim::RgbdRenderer renderer(world, cam, 1);
    lodestone::sim::Random rng(static_cast<std::uint64_t>(x * 1000) + 1);
    cv::Mat3b rgb;
    cv::Mat_<uint16_t> depth;
    // MRPT's depth frame is x forward; the renderer's camera looks along world +x at `yaw`.
    renderer.render({x, 0.2, 1.0}, yaw, rng, rgb, depth);
    RgbdFrame f;
    cv::cvtColor(rgb, f.gray, cv::COLOR_BGR2GRAY);
    f.depth = depthToMetres(depth, 0.001);
    f.intrinsics = {cam.fx, cam.fy, cam.cx, cam.cy, cam.width, cam.height};
    return f;
}
}  // namespace

TEST(RgbdVisualOdometry, RealKinectFramesAgreeWithTheGivenPoses) {
    if (!std::filesystem::exists(k3dMatch)) {
        GTEST_SKIP() << "real data absent: " << k3dMatch << " (read in place from ../shared/data)";
    }
    for (const int other : {1, 2}) {
        RgbdVisualOdometry vo;
        const auto init = vo.process(loadFrame(0));
        EXPECT_FALSE(init.success);
        EXPECT_EQ(init.state, VoState::Initializing);
        const auto r = vo.process(loadFrame(other));
        ASSERT_TRUE(r.success) << toString(r.failure) << " matches " << r.matches;
        const Eigen::Isometry3d truth = loadPose(0).inverse() * loadPose(other);
        const Eigen::Isometry3d err = truth.inverse() * r.T_ref_cur;
        const double dt = err.translation().norm(), dr = Eigen::AngleAxisd(err.rotation()).angle();
        RecordProperty("frame_" + std::to_string(other) + "_error_cm", std::to_string(100 * dt));
        EXPECT_LT(dt, 0.02) << "frame 0 -> " << other << ": " << r.inliers << " inliers";
        EXPECT_LT(dr, 1.0 * M_PI / 180) << "frame 0 -> " << other;
        EXPECT_EQ(r.state, VoState::Tracking);
    }
}

TEST(RgbdVisualOdometry, SimulatedMotionTowardsAPostersWall) {
    const auto sc = lodestone::test::boxScenario("posters");
    const lodestone::sim::World world(sc, 3);
    lodestone::sim::CameraSpec cam;
    RgbdVisualOdometry vo;
    vo.process(simulatedFrame(world, cam, 5.0, 0.0));
    const auto r = vo.process(simulatedFrame(world, cam, 5.08, 0.03));  // 8 cm on, 1.7 deg left
    ASSERT_TRUE(r.success) << toString(r.failure);
    // Optical frame: z forward, x right. Moving 8 cm forward; turning left is -y rotation.
    EXPECT_NEAR(r.T_ref_cur.translation().z(), 0.08, 0.01);
    EXPECT_NEAR(r.T_ref_cur.translation().x(), 0.0, 0.01);
    const Eigen::AngleAxisd aa(r.T_ref_cur.rotation());
    EXPECT_NEAR(aa.angle(), 0.03, 0.005);
    EXPECT_NEAR(std::abs(aa.axis().y()), 1.0, 0.05);
    EXPECT_LT(aa.axis().y() * 1.0, 0.0) << "a left turn is negative about y (down)";
}

TEST(RgbdVisualOdometry, AStepFasterThanTheCarrierIsRefused) {
    const auto sc = lodestone::test::boxScenario("posters");
    const lodestone::sim::World world(sc, 3);
    lodestone::sim::CameraSpec cam;
    auto first = simulatedFrame(world, cam, 5.0, 0.0);
    auto second = simulatedFrame(world, cam, 5.08, 0.03);  // 8 cm on, 1.7 deg left
    first.timestamp = 10.0;
    const auto after = [&](double seconds, const RgbdVisualOdometry::Params& p) {
        RgbdVisualOdometry vo(p);
        vo.process(first);
        auto f = second;
        f.timestamp = first.timestamp + seconds;
        return vo.process(f);
    };
    RgbdVisualOdometry::Params p;
    p.maxSpeed = 1.0;  // [m/s]
    p.stepError = 0.02;
    // 8 cm in one frame at 30 Hz is 2.4 m/s: more than 1 m/s and 2 cm of error allow ...
    const auto fast = after(1.0 / 30, p);
    EXPECT_FALSE(fast.success);
    EXPECT_EQ(fast.failure, VoFailure::FasterThanCarrier) << toString(fast.failure);
    // ... in a tenth of a second it is 0.8 m/s: a motion it can make.
    const auto slow = after(0.1, p);
    EXPECT_TRUE(slow.success) << toString(slow.failure);
    EXPECT_NEAR(slow.T_ref_cur.translation().z(), 0.08, 0.01);
    // The check is off by default.
    EXPECT_TRUE(after(1.0 / 30, RgbdVisualOdometry::Params()).success);
    // The turn alone: 1.7 deg in a frame is 52 deg/s, more than 10 deg/s and 0.5 deg allow.
    RgbdVisualOdometry::Params turn;
    turn.maxTurnRate = 10 * M_PI / 180;
    turn.stepErrorAngle = 0.5 * M_PI / 180;
    EXPECT_EQ(after(1.0 / 30, turn).failure, VoFailure::FasterThanCarrier);
    EXPECT_TRUE(after(0.2, turn).success);
}

TEST(RgbdVisualOdometry, AFrameIsNotChosenAsKeyframeByItsOwnMeasurement) {
    const auto sc = lodestone::test::boxScenario("posters");
    const lodestone::sim::World world(sc, 3);
    lodestone::sim::CameraSpec cam;
    const auto at = [&](double x, double t) {
        auto f = simulatedFrame(world, cam, x, 0.0);
        f.timestamp = t;
        return f;
    };
    const auto first = at(5.0, 10.0), on12 = at(5.12, 10.2), on14 = at(5.14, 10.3),
               on25 = at(5.25, 10.2);
    RgbdVisualOdometry::Params measured;  // keyframes every 10 cm (the default)
    RgbdVisualOdometry::Params predicted = measured;
    predicted.keyframeBy = RgbdVisualOdometry::Params::KeyframeBy::Predicted;
    // 12 cm measured: by its measurement the frame replaces the reference ...
    {
        RgbdVisualOdometry vo(measured);
        vo.process(first);
        ASSERT_TRUE(vo.process(on12).success);
        EXPECT_EQ(vo.referenceTimestamp(), std::optional<double>(10.2));
    }
    // ... by the prediction it does not: nothing moved before it (the first step after the
    // start), and a prior saying 5 cm keeps the reference too ...
    {
        RgbdVisualOdometry vo(predicted);
        vo.process(first);
        const auto r = vo.process(on12);
        ASSERT_TRUE(r.success) << toString(r.failure);
        EXPECT_NEAR(r.T_ref_cur.translation().z(), 0.12, 0.01) << "the step itself is as measured";
        EXPECT_EQ(vo.referenceTimestamp(), std::optional<double>(10.0));
        // ... and the next frame, the last one having been measured 12 cm on, is the keyframe.
        ASSERT_TRUE(vo.process(on14).success);
        EXPECT_EQ(vo.referenceTimestamp(), std::optional<double>(10.3));
    }
    {
        RgbdVisualOdometry vo(predicted);
        vo.process(first);
        MotionPrior prior;
        prior.T_ref_cur.translation() = Eigen::Vector3d(0, 0, 0.05);
        prior.covariance = 1e-2 * Eigen::Matrix<double, 6, 6>::Identity();
        ASSERT_TRUE(vo.process(on12, &prior).success);
        EXPECT_EQ(vo.referenceTimestamp(), std::optional<double>(10.0));
    }
    // Measured beyond twice the spacing, it is one anyway (the next frames need the overlap).
    {
        RgbdVisualOdometry vo(predicted);
        vo.process(first);
        ASSERT_TRUE(vo.process(on25).success);
        EXPECT_EQ(vo.referenceTimestamp(), std::optional<double>(10.2));
    }
}

TEST(RgbdVisualOdometryParams, KeyframesByMeasurementOrPrediction) {
    RgbdVisualOdometry::Params p;
    EXPECT_EQ(p.keyframeBy, RgbdVisualOdometry::Params::KeyframeBy::Measured);
    p.loadFromConfigFile(mrpt::config::CConfigFileMemory("[vo]\nkeyframe_by = predicted\n"), "vo");
    EXPECT_EQ(p.keyframeBy, RgbdVisualOdometry::Params::KeyframeBy::Predicted);
    try {
        p.loadFromConfigFile(mrpt::config::CConfigFileMemory("[vo]\nkeyframe_by = predictd\n"), "vo");
        FAIL() << "a misspelt keyframe_by was accepted";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("keyframe_by"), std::string::npos) << e.what();
    }
}

TEST(RgbdVisualOdometryParams, TheCarrierBoundsAreReadAndChecked) {
    RgbdVisualOdometry::Params p;
    mrpt::config::CConfigFileMemory ini(
        "[vo]\nmax_speed = 2.5\nstep_error = 0.04\nmax_turn_rate_deg = 180\nstep_error_deg = 2\n");
    p.loadFromConfigFile(ini, "vo");
    EXPECT_DOUBLE_EQ(p.maxSpeed, 2.5);
    EXPECT_DOUBLE_EQ(p.stepError, 0.04);
    EXPECT_NEAR(p.maxTurnRate, M_PI, 1e-12);
    EXPECT_NEAR(p.stepErrorAngle, 2 * M_PI / 180, 1e-12);
    mrpt::config::CConfigFileMemory bad("[vo]\nmax_speed = -1\n");
    try {
        RgbdVisualOdometry::Params q;
        q.loadFromConfigFile(bad, "vo");
        FAIL() << "a negative speed was accepted";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("max_speed"), std::string::npos) << e.what();
    }
}

TEST(RgbdVisualOdometry, AMotionPriorGuidesTheMatchingAndAWrongOneFallsBack) {
    const auto sc = lodestone::test::boxScenario("posters");
    const lodestone::sim::World world(sc, 3);
    lodestone::sim::CameraSpec cam;
    // The true motion in the reference's optical frame: 8 cm forward, 1.7 deg left.
    Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
    truth.linear() = Eigen::AngleAxisd(-0.03, Eigen::Vector3d::UnitY()).toRotationMatrix();
    truth.translation() = Eigen::Vector3d(0, 0, 0.08);
    MotionPrior prior;
    prior.T_ref_cur = truth;
    prior.covariance.setZero();
    prior.covariance.diagonal() << 3e-4, 3e-4, 3e-4, 1e-4, 1e-4, 1e-4;  // 1 deg, 1 cm
    const auto first = simulatedFrame(world, cam, 5.0, 0.0);
    const auto second = simulatedFrame(world, cam, 5.08, 0.03);

    RgbdVisualOdometry brute, guided;
    brute.process(first);
    guided.process(first);
    EXPECT_EQ(guided.referenceTimestamp(), std::optional<double>(first.timestamp));
    const auto b = brute.process(second);
    const auto g = guided.process(second, &prior);
    ASSERT_TRUE(b.success && g.success) << toString(g.failure);
    EXPECT_FALSE(b.guided);
    EXPECT_TRUE(g.guided);
    EXPECT_LT((g.T_ref_cur.translation() - truth.translation()).norm(), 0.01);
    EXPECT_LT(Eigen::AngleAxisd(g.T_ref_cur.rotation().transpose() * truth.rotation()).angle(),
              0.005);
    EXPECT_GE(g.inliers, b.inliers * 9 / 10) << "the gate keeps what brute force found";
    EXPECT_EQ(guided.totals().guided, 1u);

    // A prior 40 cm sideways of the truth (a push the wheels did not feel): the gates miss the
    // true keypoints, and brute force finds the motion.
    RgbdVisualOdometry misled;
    misled.process(first);
    MotionPrior wrong = prior;
    wrong.T_ref_cur.translation() += Eigen::Vector3d(0.4, 0, 0);
    const auto m = misled.process(second, &wrong);
    ASSERT_TRUE(m.success) << toString(m.failure);
    EXPECT_FALSE(m.guided);
    EXPECT_EQ(misled.totals().guidedFallback, 1u);
    EXPECT_LT((m.T_ref_cur.translation() - truth.translation()).norm(), 0.01);
}

TEST(RgbdVisualOdometry, PlainWallsMissingDepthAndNaNsFailThenLost) {
    const auto plain = lodestone::test::boxScenario("plain");
    const lodestone::sim::World world(plain, 3);
    lodestone::sim::CameraSpec cam;
    RgbdVisualOdometry::Params p;
    p.lostAfter = 3;
    RgbdVisualOdometry vo(p);
    const auto blank = simulatedFrame(world, cam, 6.0, 0.0);
    auto r = vo.process(blank);  // nothing to initialize on
    EXPECT_FALSE(r.success);
    EXPECT_EQ(r.failure, VoFailure::FewFeatures);

    // Initialize on a textured frame, then feed featureless, depthless and NaN frames.
    const auto posters = lodestone::test::boxScenario("posters");
    const lodestone::sim::World textured(posters, 3);
    r = vo.process(simulatedFrame(textured, cam, 5.0, 0.0));
    EXPECT_EQ(r.state, VoState::Initializing);
    RgbdFrame noDepth = simulatedFrame(textured, cam, 5.02, 0.0);
    noDepth.depth.setTo(0);
    RgbdFrame nanDepth = simulatedFrame(textured, cam, 5.02, 0.0);
    nanDepth.depth.setTo(std::numeric_limits<float>::quiet_NaN());
    RgbdFrame empty;
    int failures = 0;
    for (const RgbdFrame* f : std::vector<const RgbdFrame*>{&blank, &noDepth, &nanDepth}) {
        r = vo.process(*f);
        EXPECT_FALSE(r.success);
        ++failures;
        EXPECT_EQ(r.state, failures < 3 ? VoState::Initializing : VoState::Lost) << failures;
    }
    EXPECT_FALSE(vo.process(empty).success);
    EXPECT_EQ(vo.state(), VoState::Lost);
    // A textured frame re-initializes, the next one tracks again.
    vo.process(simulatedFrame(textured, cam, 5.1, 0.0));
    EXPECT_EQ(vo.state(), VoState::Initializing);
    r = vo.process(simulatedFrame(textured, cam, 5.15, 0.0));
    EXPECT_TRUE(r.success);
    EXPECT_EQ(r.state, VoState::Tracking);
}

// The grey image goes blank (lights out, a lens cap of texture): with depth alignment the frame's
// depth, aligned with the keyframe's, still gives the motion - and says which directions it pinned.
TEST(RgbdVisualOdometry, WhereFeaturesFailTheDepthIsAligned) {
    const auto sc = lodestone::test::boxScenario("posters");
    const lodestone::sim::World world(sc, 3);
    lodestone::sim::CameraSpec cam;
    const auto first = simulatedFrame(world, cam, 5.5, 0.5);  // the posters wall, a side wall, the floor
    auto second = simulatedFrame(world, cam, 5.56, 0.52);
    second.gray.setTo(0);
    second.timestamp = first.timestamp + 1.0 / 30;
    // 6 cm on along +x in the world, turned 1.15 deg left: in the reference's optical frame.
    const double yaw = 0.5;
    const Eigen::Vector3d moveWorld(0.06, 0, 0);
    const Eigen::Vector3d moveOptical(-(-std::sin(yaw) * moveWorld.x()), 0, std::cos(yaw) * moveWorld.x());

    RgbdVisualOdometry::Params p;
    RgbdVisualOdometry featuresOnly(p);
    featuresOnly.process(first);
    const auto f = featuresOnly.process(second);
    EXPECT_FALSE(f.success);
    EXPECT_EQ(f.failure, VoFailure::FewFeatures);

    p.depthAlignment = true;
    RgbdVisualOdometry withDepth(p);
    withDepth.process(first);
    const auto d = withDepth.process(second);
    ASSERT_TRUE(d.success) << "depth observed " << d.depthObserved;
    EXPECT_TRUE(d.depthAligned);
    EXPECT_EQ(d.failure, VoFailure::FewFeatures) << "why the features failed";
    EXPECT_GE(d.depthObserved, 5);
    EXPECT_LT((d.T_ref_cur.translation() - moveOptical).norm(), 0.01)
        << d.T_ref_cur.translation().transpose() << " vs " << moveOptical.transpose();
    EXPECT_NEAR(Eigen::AngleAxisd(d.T_ref_cur.rotation()).angle(), 0.02, 0.003);
    EXPECT_EQ(withDepth.totals().depthAligned, 1u);
}

// Where the features align as well, features and depth are solved as one: the motion stays
// right and the frame says so.
TEST(RgbdVisualOdometry, FeaturesAndDepthSolvedAsOne) {
    const auto sc = lodestone::test::boxScenario("posters");
    const lodestone::sim::World world(sc, 3);
    lodestone::sim::CameraSpec cam;
    RgbdVisualOdometry::Params p;
    p.depthAlignment = true;
    p.depthWithFeatures = true;
    RgbdVisualOdometry vo(p);
    vo.process(simulatedFrame(world, cam, 5.5, 0.5));
    const auto r = vo.process(simulatedFrame(world, cam, 5.56, 0.52));
    ASSERT_TRUE(r.success) << toString(r.failure);
    EXPECT_TRUE(r.depthJoined);
    EXPECT_FALSE(r.depthAligned);
    const double yaw = 0.5;
    const Eigen::Vector3d moveOptical(0.06 * std::sin(yaw), 0, 0.06 * std::cos(yaw));
    EXPECT_LT((r.T_ref_cur.translation() - moveOptical).norm(), 0.01);
    EXPECT_NEAR(Eigen::AngleAxisd(r.T_ref_cur.rotation()).angle(), 0.02, 0.003);
    EXPECT_EQ(vo.totals().depthJoined, 1u);
}

// A gyro's rotation starts the depth alignment where the features fail: the true one aligns, one
// 25 degrees off leads it astray (so it is what the alignment starts from).
TEST(RgbdVisualOdometry, WhereFeaturesFailTheGyroRotationStartsTheDepth) {
    const auto sc = lodestone::test::boxScenario("posters");
    const lodestone::sim::World world(sc, 3);
    lodestone::sim::CameraSpec cam;
    const auto first = simulatedFrame(world, cam, 5.5, 0.5);
    auto second = simulatedFrame(world, cam, 5.56, 0.55);
    second.gray.setTo(0);
    second.timestamp = first.timestamp + 1.0 / 30;
    RgbdVisualOdometry::Params p;
    p.depthAlignment = true;
    // A left turn of 0.05 rad is negative about the optical y axis (down).
    RotationPrior right;
    right.R_ref_cur = Eigen::AngleAxisd(-0.05, Eigen::Vector3d::UnitY()).toRotationMatrix();
    RotationPrior wrong = right;
    wrong.R_ref_cur = Eigen::AngleAxisd(-0.5, Eigen::Vector3d::UnitY()).toRotationMatrix();
    RgbdVisualOdometry a(p), b(p);
    a.process(first);
    b.process(first);
    const auto good = a.process(second, nullptr, &right);
    ASSERT_TRUE(good.success && good.depthAligned);
    EXPECT_NEAR(Eigen::AngleAxisd(good.T_ref_cur.rotation()).angle(), 0.05, 0.003);
    const auto bad = b.process(second, nullptr, &wrong);
    EXPECT_FALSE(bad.success && std::abs(Eigen::AngleAxisd(bad.T_ref_cur.rotation()).angle() - 0.05) < 0.003);
}

// A gyro's rotation joins the features' motion where asked: in tilt only, a heading 1 deg off
// leaves the features' heading alone; all of it, as sure as the features, the heading meets it
// half way. The camera's own motion stays reported apart.
TEST(RgbdVisualOdometry, TheGyrosRotationJoinsTheFeaturesWhereAsked) {
    const auto sc = lodestone::test::boxScenario("posters");
    const lodestone::sim::World world(sc, 3);
    lodestone::sim::CameraSpec cam;
    RotationPrior gyro;  // the truth's 1.7 deg left (-y in the optical frame), and 1 deg more
    gyro.R_ref_cur = Eigen::AngleAxisd(-0.03 - M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix();
    gyro.vertical = -Eigen::Vector3d::UnitY();
    const auto run = [&](RgbdVisualOdometry::Params::GyroJoin join) {
        RgbdVisualOdometry::Params p;
        p.gyroWithFeatures = join;
        RgbdVisualOdometry vo(p);
        vo.process(simulatedFrame(world, cam, 5.0, 0.0), nullptr, &gyro);
        return vo.process(simulatedFrame(world, cam, 5.08, 0.03), nullptr, &gyro);
    };
    const auto heading = [](const Eigen::Isometry3d& T) {  // about optical y
        const Eigen::AngleAxisd aa(T.rotation());
        return aa.angle() * aa.axis().y();
    };
    const auto off = run(RgbdVisualOdometry::Params::GyroJoin::Off);
    ASSERT_TRUE(off.success);
    gyro.sigma = std::sqrt(off.covariance(1, 1));  // (as sure as the features about y)
    const auto tilt = run(RgbdVisualOdometry::Params::GyroJoin::Tilt);
    const auto all = run(RgbdVisualOdometry::Params::GyroJoin::All);
    ASSERT_TRUE(tilt.success && all.success);
    EXPECT_FALSE(off.gyroJoined);
    EXPECT_TRUE(tilt.gyroJoined);
    EXPECT_TRUE(all.gyroJoined);
    // (the tilt it takes moves the heading only by their correlation in the features' fit)
    EXPECT_NEAR(heading(tilt.T_ref_cur), heading(off.T_ref_cur), 0.02 * M_PI / 180);
    const double gap = heading(Eigen::Isometry3d(gyro.R_ref_cur)) - heading(off.T_ref_cur);
    EXPECT_NEAR(heading(all.T_ref_cur) - heading(off.T_ref_cur), gap / 2, 0.1 * std::abs(gap));
    EXPECT_LT(all.covariance(1, 1), 0.6 * off.covariance(1, 1));
    EXPECT_TRUE(all.T_ref_cur_camera.isApprox(off.T_ref_cur));
    EXPECT_TRUE(all.covariance_camera.isApprox(off.covariance));
}

TEST(RgbdVisualOdometryParams, TheGyroJoinIsOffTiltOrAll) {
    RgbdVisualOdometry::Params p;
    mrpt::config::CConfigFileMemory ini("[vo]\ngyro_with_features = tilt\n");
    p.loadFromConfigFile(ini, "vo");
    EXPECT_EQ(p.gyroWithFeatures, RgbdVisualOdometry::Params::GyroJoin::Tilt);
    mrpt::config::CConfigFileMemory bad("[vo]\ngyro_with_features = yes\n");
    RgbdVisualOdometry::Params q;
    EXPECT_THROW(q.loadFromConfigFile(bad, "vo"), std::exception);
}
