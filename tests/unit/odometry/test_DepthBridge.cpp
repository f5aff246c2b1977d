#include <gtest/gtest.h>
#include <lodestone/odometry/DepthBridge.h>
#include <lodestone/sim/World.h>

#include <cmath>

#include "SimTestFrames.h"
#include "SimTestWorlds.h"

using lodestone::odometry::DepthBridge;
using lodestone::odometry::FadingVelocity;

namespace {
constexpr double kRate = 30;  // [Hz]

/** A frame with no depth anywhere: the bridge is its motion model alone. */
lodestone::vision::RgbdFrame blankFrame() {
    lodestone::vision::RgbdFrame blank;
    blank.intrinsics = {570.3, 570.3, 319.5, 239.5, 640, 480};
    blank.depth = cv::Mat::zeros(480, 640, CV_32FC1);
    return blank;
}
}  // namespace

// With no depth in any frame the bridge is the fading velocity's, mean and variance alike.
TEST(DepthBridge, WithoutDepthItIsTheFadingVelocitysBridge) {
    const lodestone::vision::RgbdFrame blank = blankFrame();
    DepthBridge::Params p;
    p.motion = FadingVelocity{0.5, 1.0};
    DepthBridge bridge(p);
    const Eigen::Vector3d v0(0.3, -0.1, 0.02);
    const double v0Sigma = 0.03;
    bridge.start(10.0, blank, lodestone::test::opticalInCamera(), v0,
                 v0Sigma * v0Sigma * Eigen::Matrix3d::Identity());
    for (int k = 1; k <= 120; ++k) {
        bridge.add(10.0 + k / kRate, blank, lodestone::test::opticalInCamera(),
                   Eigen::Matrix3d::Identity());
    }
    const double gap = 120 / kRate;
    const Eigen::Vector3d mean = p.motion.meanDisplacement(v0, gap);
    const double variance = p.motion.displacementVariance(gap, v0Sigma);
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(bridge.displacement()(a), mean(a), 1e-9);
        EXPECT_NEAR(bridge.covariance()(a, a), variance, 1e-9 * variance);
    }
    EXPECT_EQ(bridge.aligned(), 0);
    // The velocity it ends with (what a gap after a restart on this frame starts from): the
    // model's too.
    Eigen::Vector3d v = v0;
    Eigen::Matrix3d C = v0Sigma * v0Sigma * Eigen::Matrix3d::Identity();
    p.motion.fadeVelocity(gap, v, C);
    EXPECT_NEAR((bridge.velocity() - v).norm(), 0, 1e-9);
    EXPECT_NEAR((bridge.velocityCovariance() - C).norm(), 0, 1e-9);
}

// With a cruise and no depth the bridge is the model's with it: the carrier keeps its pace
// (0.3 m/s over 4 s: 1.2 m, where fading to rest from the same start carries it 0.3 m). A robot
// that stopped and turns on the spot (its cruise learnt on a straight corridor: no turn that
// fast in it) stays where it stood, and drives on at its pace along its new heading.
TEST(DepthBridge, WithoutDepthACruisingCarrierKeepsItsPaceAndStopsToTurn) {
    const lodestone::vision::RgbdFrame blank = blankFrame();
    DepthBridge::Params p;
    p.motion = FadingVelocity{0.5, 1.0};
    lodestone::odometry::CruiseVelocity cruise(10.0);
    for (int k = 0; k < 900; ++k) cruise.add(Eigen::Vector3d(0.3 / kRate, 0, 0), 1 / kRate, 0.0);
    const Eigen::Vector3d pace(0.3, 0, 0);
    ASSERT_NEAR((cruise.at(0) - pace).norm(), 0, 1e-9);
    const Eigen::Matrix3d C0 = 0.03 * 0.03 * Eigen::Matrix3d::Identity();
    DepthBridge straight(p);
    straight.start(10.0, blank, lodestone::test::opticalInCamera(), pace, C0, Eigen::Vector3d::UnitZ(), cruise);
    for (int k = 1; k <= 120; ++k)
        straight.add(10.0 + k / kRate, blank, lodestone::test::opticalInCamera(), Eigen::Matrix3d::Identity());
    EXPECT_NEAR((straight.displacement() - p.motion.meanDisplacement(pace, 4.0, pace)).norm(), 0, 1e-9);
    EXPECT_NEAR(straight.displacement().x(), 1.2, 1e-9);
    EXPECT_NEAR(straight.covariance()(0, 0), p.motion.displacementVariance(4.0, 0.03), 1e-9);

    DepthBridge turning(p);
    turning.start(10.0, blank, lodestone::test::opticalInCamera(), Eigen::Vector3d::Zero(), C0,
                  Eigen::Vector3d::UnitZ(), cruise);
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    const int turn = 78;  // a quarter turn at 35 deg/s
    for (int k = 1; k <= turn; ++k) {
        R = Eigen::AngleAxisd(M_PI / 2 * k / turn, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        turning.add(10.0 + k / kRate, blank, lodestone::test::opticalInCamera(), R);
    }
    EXPECT_LT(turning.displacement().norm(), 1e-9) << turning.displacement().transpose();
    for (int k = turn + 1; k <= turn + 90; ++k)  // 3 s straight on
        turning.add(10.0 + k / kRate, blank, lodestone::test::opticalInCamera(), R);
    // (from rest towards the pace over 3 s: 0.3 (3 - (1 - e^-3)) along the new heading, y)
    EXPECT_NEAR((turning.velocity() - R * pace).norm(), 0, 0.3 * std::exp(-3) + 1e-6);
    EXPECT_NEAR(turning.displacement().y(), 0.3 * (3 - (1 - std::exp(-3))), 0.01) << turning.displacement().transpose();
    EXPECT_NEAR(turning.displacement().x(), 0, 0.01);
    EXPECT_EQ(turning.beyondCruise(), turn);
    EXPECT_EQ(turning.cruising(), 90);
    EXPECT_EQ(straight.cruising(), 120);
}

// Walking 1 m at a plain wall (2 m from it to 1 m, nothing else in view) while drifting 0.2 m
// sideways, the velocity before the gap a tenth of the truth's: the depth measures the approach,
// which the motion model alone puts at 0.1 m, and says nothing of the drift along the wall -
// there the model's guess stands with its loose covariance, the truth inside it.
TEST(DepthBridge, TheDepthMeasuresTheApproachToAPlainWallAndNotTheDriftAlongIt) {
    const lodestone::sim::World world(lodestone::test::boxScenario("plain"), 3);
    const auto at = [](double s) {  // the front wall is x = 8
        return lodestone::test::cameraPose({6.0 + s, 0.2 * s, 1.25}, 0.0);
    };
    const Eigen::Isometry3d camera = lodestone::test::opticalInCamera();  // (robot = camera)
    DepthBridge bridge;
    bridge.start(0.0, lodestone::test::render(world, at(0), 1), camera, {0.033, 0, 0},
                 0.03 * 0.03 * Eigen::Matrix3d::Identity());
    const int frames = 90;  // 3 s
    for (int k = 1; k <= frames; ++k) {
        bridge.add(k / kRate, lodestone::test::render(world, at(double(k) / frames), 1 + k), camera,
                   Eigen::Matrix3d::Identity());
    }
    EXPECT_GE(bridge.aligned(), frames - 2);
    EXPECT_EQ(bridge.rejected(), 0);
    const Eigen::Vector3d d = bridge.displacement();
    const Eigen::Matrix3d P = bridge.covariance();
    EXPECT_NEAR(d.x(), 1.0, 0.01) << d.transpose();
    EXPECT_LT(std::sqrt(P(0, 0)), 0.02);
    // Along the wall: loose (the model's), and honest about the drift it could not see.
    EXPECT_GT(std::sqrt(P(1, 1)), 0.5);
    EXPECT_GT(std::sqrt(P(2, 2)), 0.5);
    EXPECT_LT(std::abs(d.y() - 0.2), 3 * std::sqrt(P(1, 1)));
    EXPECT_LT(std::abs(d.z()), 0.05);
}

// A hand's sway VO measured at the gap's start (0.13 m/s sideways, surely - as the first
// alignments of a gap once set it) while the carrier walks straight at a plain wall for 3 s,
// which measures the approach and nothing sideways: the walk persists, the sway turns back
// within a half step. Carried on at the walk's persistence it put the bridge 0.12 m sideways.
TEST(DepthBridge, AHandsSwayIsNotCarriedAcrossAGap) {
    const lodestone::sim::World world(lodestone::test::boxScenario("plain"), 3);
    const auto at = [](double s) { return lodestone::test::cameraPose({6.0 + s, 0.0, 1.25}, 0.0); };
    const Eigen::Isometry3d camera = lodestone::test::opticalInCamera();  // (robot = camera)
    DepthBridge::Params p;
    p.motion.acrossSeconds = 0.25;
    const int frames = 90;  // 3 s
    const auto run = [&](const DepthBridge::Params& params) {
        DepthBridge bridge(params);
        bridge.start(0.0, lodestone::test::render(world, at(0), 1), camera, {0.33, 0.13, 0},
                     0.01 * 0.01 * Eigen::Matrix3d::Identity());
        for (int k = 1; k <= frames; ++k) {
            bridge.add(k / kRate, lodestone::test::render(world, at(double(k) / frames), 1 + k),
                       camera, Eigen::Matrix3d::Identity());
        }
        return bridge;
    };
    const DepthBridge bridge = run(p);
    EXPECT_GE(bridge.aligned(), frames - 2);
    const Eigen::Vector3d d = bridge.displacement();
    EXPECT_NEAR(d.x(), 1.0, 0.01) << d.transpose();
    EXPECT_LT(std::abs(d.y()), 0.04) << d.transpose();  // (0.13 x 0.25 s: 0.033)
    EXPECT_LT(std::abs(d.y()), 3 * std::sqrt(bridge.covariance()(1, 1)));
    // The same with the sway persisting as the walk does: a tenth of a metre sideways.
    p.motion.acrossSeconds = 0;
    EXPECT_GT(run(p).displacement().y(), 0.1);
}

// A robot's camera (0.45 m up, 0.10 m ahead of the axle) turning a quarter turn in place 1.2 m
// from a plain wall, the floor in view below it: the optical centre swings round the axle, and
// the bridge, given the gyro's turn, finds the robot where it stood.
TEST(DepthBridge, ARobotTurningInPlaceBeforeAWallStaysWhereItStood) {
    const lodestone::sim::World world(lodestone::test::boxScenario("plain"), 3);
    Eigen::Isometry3d cameraOnRobot = Eigen::Isometry3d::Identity();
    cameraOnRobot.translation() << 0.10, 0, 0.45;
    const auto robotAt = [](double yaw) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        T.translation() << 6.7, 0.0, 0.0;
        return T;
    };
    const Eigen::Isometry3d optical = cameraOnRobot * lodestone::test::opticalInCamera();
    DepthBridge bridge;
    bridge.start(0.0, lodestone::test::render(world, robotAt(0) * cameraOnRobot, 1), optical,
                 Eigen::Vector3d::Zero(), 0.03 * 0.03 * Eigen::Matrix3d::Identity());
    const int frames = 75;  // 2.5 s at 36 deg/s
    for (int k = 1; k <= frames; ++k) {
        const double yaw = M_PI / 2 * k / frames;
        bridge.add(k / kRate, lodestone::test::render(world, robotAt(yaw) * cameraOnRobot, 1 + k),
                   optical, Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix());
    }
    EXPECT_GE(bridge.aligned(), frames - 2);
    const Eigen::Vector3d d = bridge.displacement();
    EXPECT_LT(d.norm(), 0.02) << d.transpose();
    const Eigen::Vector3d sigma = bridge.covariance().diagonal().cwiseSqrt();
    for (int a = 0; a < 3; ++a) EXPECT_LT(std::abs(d(a)), 3 * sigma(a) + 0.005) << a;
}

// A vertical velocity nothing measures (VO's last frames before a plain wall drift in height)
// would carry the bridge a metre up over a few seconds; a carrier's height wanders centimetres,
// and with that prior the bridge stays within it - along the other axes it is unchanged.
TEST(DepthBridge, TheCarriersHeightHoldsWhereNothingMeasuresIt) {
    const lodestone::vision::RgbdFrame blank = blankFrame();
    DepthBridge::Params p;
    DepthBridge free(p);
    p.heightSigma = 0.1;
    DepthBridge held(p);
    const Eigen::Vector3d v0(0.3, 0.0, 0.6);
    for (DepthBridge* b : {&free, &held}) {
        b->start(0.0, blank, lodestone::test::opticalInCamera(), v0, 0.5 * 0.5 * Eigen::Matrix3d::Identity());
        for (int k = 1; k <= 120; ++k)
            b->add(k / kRate, blank, lodestone::test::opticalInCamera(), Eigen::Matrix3d::Identity());
    }
    EXPECT_GT(free.displacement().z(), 0.5);
    EXPECT_LT(std::abs(held.displacement().z()), 0.02);
    EXPECT_LT(std::sqrt(held.covariance()(2, 2)), 0.1);
    EXPECT_NEAR(held.displacement().x(), free.displacement().x(), 1e-12);
    EXPECT_NEAR(held.covariance()(0, 0), free.covariance()(0, 0), 1e-12);
    // The velocity the bridge hands on to a gap after it is conditioned alike (the two are
    // correlated): held at its height, the carrier is not still climbing as the free model
    // has it, and its vertical velocity is surer.
    EXPECT_GT(free.velocity().z(), 0.0);
    EXPECT_LT(held.velocity().z(), free.velocity().z());
    EXPECT_LT(held.velocityCovariance()(2, 2), free.velocityCovariance()(2, 2));
    EXPECT_NEAR(held.velocity().x(), free.velocity().x(), 1e-12);
}

// No gyro: a hand-held camera (1.25 m up) turning a quarter turn in place at a plain corner, 1 m
// from each wall, its turn rate at the start unknown (zero, spread as a carrier's). The depth
// sees one wall, then the corner, then the other: it measures the turn to a degree, says how
// sure it is honestly, and finds the camera where it stood.
TEST(DepthBridge, WithoutAGyroTheDepthMeasuresAQuarterTurnAtAPlainCorner) {
    const lodestone::sim::World world(lodestone::test::boxScenario("plain"), 3);
    const auto at = [](double yaw) { return lodestone::test::cameraPose({7.0, 2.0, 1.25}, yaw); };
    const Eigen::Isometry3d camera = lodestone::test::opticalInCamera();  // (robot = camera)
    DepthBridge::Params p;
    p.turn.tiltSigma = 5 * M_PI / 180;
    DepthBridge bridge(p);
    bridge.start(0.0, lodestone::test::render(world, at(0), 1), camera, Eigen::Vector3d::Zero(),
                 0.03 * 0.03 * Eigen::Matrix3d::Identity());
    bridge.startTurn(Eigen::Vector3d::Zero(), 0.5 * 0.5 * Eigen::Matrix3d::Identity());
    ASSERT_TRUE(bridge.turning());
    const int frames = 75;  // 2.5 s at 36 deg/s
    for (int k = 1; k <= frames; ++k)
        bridge.add(k / kRate, lodestone::test::render(world, at(M_PI / 2 * k / frames), 1 + k), camera);
    EXPECT_GE(bridge.aligned(), frames - 2);
    const Eigen::Matrix3d truth =
        Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::AngleAxisd error(truth.transpose() * bridge.rotation());
    const Eigen::Vector3d e = error.angle() * error.axis();
    EXPECT_LT(error.angle(), 1.0 * M_PI / 180) << e.transpose();
    const Eigen::Matrix3d P = bridge.rotationCovariance();
    // The turn about the vertical measured: to a degree or two (no alignment's turn surer than
    // one depth point over the view's spread), where the fading rate alone is tens of degrees.
    EXPECT_LT(std::sqrt(P(2, 2)), 2.0 * M_PI / 180);
    EXPECT_LT(e.dot(P.ldlt().solve(e)), 16.27);       // honest: inside its own 99.9 %
    EXPECT_LT(bridge.displacement().norm(), 0.05) << bridge.displacement().transpose();
}

// No gyro and no depth: the turn is the fading rate's guess - the rate at the start carried
// as FadingVelocity carries a velocity, with that model's spread per axis.
TEST(DepthBridge, WithoutAGyroOrDepthTheTurnIsTheFadingRatesGuess) {
    const lodestone::vision::RgbdFrame blank = blankFrame();
    DepthBridge::Params p;
    p.turn.rate = FadingVelocity{0.5, 1.0};
    DepthBridge bridge(p);
    bridge.start(0.0, blank, lodestone::test::opticalInCamera(), Eigen::Vector3d::Zero(),
                 0.03 * 0.03 * Eigen::Matrix3d::Identity());
    const Eigen::Vector3d w0(0, 0, 0.4);
    const double w0Sigma = 0.05;
    bridge.startTurn(w0, w0Sigma * w0Sigma * Eigen::Matrix3d::Identity());
    for (int k = 1; k <= 60; ++k) bridge.add(k / kRate, blank, lodestone::test::opticalInCamera());
    const double gap = 60 / kRate;
    const Eigen::AngleAxisd turned(bridge.rotation());
    EXPECT_NEAR(turned.angle(), p.turn.rate.meanDisplacement(w0, gap).z(), 1e-9);
    EXPECT_NEAR(turned.axis().z(), 1.0, 1e-9);
    const double variance = p.turn.rate.displacementVariance(gap, w0Sigma);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(bridge.rotationCovariance()(a, a), variance, 1e-9 * variance);
    EXPECT_EQ(bridge.aligned(), 0);
}

// No gyro, a hand-held camera standing 1 m before a plain wall (nothing else in view), the turn
// rate at the start wrong: VO's last frames claim a roll of 20 deg/s. The wall measures the
// pitch and the yaw (its normal) and not the roll about its normal - left to the rate's guess it
// rolls 20 deg off and claims a few; the carrier's tilt held to 5 deg keeps it there, honestly.
TEST(DepthBridge, WithoutAGyroTheRollAboutAPlainWallsNormalIsHeldByTheCarriersTilt) {
    const lodestone::sim::World world(lodestone::test::boxScenario("plain"), 3);
    const Eigen::Isometry3d pose = lodestone::test::cameraPose({7.0, 0.0, 1.25}, 0.0);
    const Eigen::Isometry3d camera = lodestone::test::opticalInCamera();  // (robot = camera)
    const Eigen::Vector3d wrongRate(20 * M_PI / 180, 0, 0);
    const auto rollAfter = [&](double tiltSigma, Eigen::Matrix3d& covariance) {
        DepthBridge::Params p;
        p.turn.tiltSigma = tiltSigma;
        DepthBridge bridge(p);
        bridge.start(0.0, lodestone::test::render(world, pose, 1), camera, Eigen::Vector3d::Zero(),
                     0.03 * 0.03 * Eigen::Matrix3d::Identity());
        bridge.startTurn(wrongRate, std::pow(2 * M_PI / 180, 2) * Eigen::Matrix3d::Identity());
        for (int k = 1; k <= 90; ++k) bridge.add(k / kRate, lodestone::test::render(world, pose, 1 + k), camera);
        EXPECT_GE(bridge.aligned(), 88);
        covariance = bridge.rotationCovariance();
        const Eigen::AngleAxisd turned(bridge.rotation());
        return turned.angle() * turned.axis();
    };
    Eigen::Matrix3d free, held;
    const Eigen::Vector3d wandered = rollAfter(0, free), kept = rollAfter(5 * M_PI / 180, held);
    EXPECT_GT(std::abs(wandered.x()), 10 * M_PI / 180) << "the wall does not see the roll";
    EXPECT_LT(std::abs(kept.x()), 5 * M_PI / 180) << kept.transpose();
    EXPECT_LT(std::abs(kept.x()), 3 * std::sqrt(held(0, 0)));
    EXPECT_LT(std::sqrt(held(0, 0)), 1.5 * 5 * M_PI / 180);  // (about the tilt it is held to)
    for (const auto& r : {wandered, kept}) {  // (the wall's own directions: measured either way)
        EXPECT_LT(std::abs(r.y()), 0.5 * M_PI / 180) << r.transpose();
        EXPECT_LT(std::abs(r.z()), 0.5 * M_PI / 180) << r.transpose();
    }
}
