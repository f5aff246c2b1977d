// A camera-only recording as a user meets one: the simulated office rendered at
// 320x240 / 15 Hz with its wheel odometry taken out - what a handheld or dataset sequence
// looks like to lodestone-slam. With rgbd_only.ini it runs on VO alone in 6-DoF and tracks
// the truth; with slam.ini it is refused with a message that names rgbd_only.ini.
#include <gtest/gtest.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/io/RawlogWriter.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/obs/registerAllClasses.h>
#include <lodestone/odometry/FadingVelocity.h>
#include <mrpt/graphs/CNetworkOfPoses.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationIMU.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <map>
#include <regex>
#include <sstream>

#include "CameraOnlyRuns.h"

using namespace lodestone::test::camera_only;
namespace fs = std::filesystem;

TEST(CameraOnlySlam, RunsWithRgbdOnlyAndIsRefusedWithANamedWayOutElsewhere) {
    lodestone::test::TempDir dir;
    const std::string rawlog = cameraOnlyOffice(dir);

    const auto run = lodestone::test::runCommand(
        kSlam + " --rawlog " + rawlog + " --config " + kConfigDir + "/slam/rgbd_only.ini --out " +
        dir.file("out") + " --ground-truth " + dir.file("camera.gt.tum") + " --quiet");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const auto traj = lodestone::io::readTumTrajectory(dir.file("out/trajectory.tum"));
    EXPECT_GT(traj.size(), 50u);
    // VO alone over the office's 28 s: centimetres (measured 0.014 m; wheels + VO: 0.0035).
    const double ate = ateOf(run.output);
    EXPECT_GT(ate, 0) << run.output;
    EXPECT_LT(ate, 0.03) << run.output;

    for (const char* ini : {"slam.ini", "visual_only.ini"}) {
        const auto refused = lodestone::test::runCommand(kSlam + " --rawlog " + rawlog + " --config " +
                                                         kConfigDir + "/slam/" + ini + " --out " +
                                                         dir.file(std::string("no_") + ini));
        EXPECT_EQ(refused.exitCode, 1) << ini;
        EXPECT_NE(refused.output.find("rgbd_only.ini"), std::string::npos) << refused.output;
    }
}


TEST(CameraOnlySlam, VoLostWithNoWheelsRelocalizesOnTheViewThatCameBack) {
    lodestone::test::TempDir dir;
    // Frames 150-169 (1.3 s) see nothing: VO fails, goes LOST after 5, restarts at frame 170,
    // 0.4 m further on, looking at what it saw before the lens was covered.
    const std::string rawlog = cameraOnlyOffice(dir, 150, 170);
    const auto run = lodestone::test::runCommand(
        kSlam + " --rawlog " + rawlog + " --config " + kConfigDir + "/slam/rgbd_only.ini --out " +
        dir.file("out") + " --ground-truth " + dir.file("camera.gt.tum") + " --quiet");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string report = reportOf(dir.file("out"));
    EXPECT_NE(report.find("\"vo_gaps\": 1"), std::string::npos) << report;
    EXPECT_NE(report.find("\"vo_gaps_relocalized\": 1"), std::string::npos) << report;
    // (the right view is not refused: it agrees with where the last velocity carried the camera)
    EXPECT_NE(report.find("\"vo_relocalizations_against_the_motion_model\": 0"), std::string::npos)
        << report;
    EXPECT_NE(report.find("\"segments\": 1"), std::string::npos) << report;
    // ... and rightly: the trajectory stays as good as without the gap (< 0.03 m).
    const double ate = ateOf(run.output);
    EXPECT_GT(ate, 0) << run.output;
    EXPECT_LT(ate, 0.03) << run.output;
    const auto traj = lodestone::io::readTumTrajectory(dir.file("out/trajectory.tum"));
    ASSERT_FALSE(traj.empty());
    EXPECT_GT(traj.back().timestamp - traj.front().timestamp, 20.0);  // nodes go on after it
}

// The colour goes blank but the depth stays (lights out): depth alignment keeps tracking
// through it - no gap, one segment, the trajectory as good as without it.
TEST(CameraOnlySlam, ABlankImageWithDepthIsTrackedByTheDepth) {
    lodestone::test::TempDir dir;
    const std::string rawlog = cameraOnlyOffice(dir, 150, 170, true);
    const auto run = lodestone::test::runCommand(
        kSlam + " --rawlog " + rawlog + " --config " + kConfigDir + "/slam/rgbd_only.ini --out " +
        dir.file("out") + " --ground-truth " + dir.file("camera.gt.tum") + " --quiet");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string report = reportOf(dir.file("out"));
    EXPECT_NE(report.find("\"vo_gaps\": 0"), std::string::npos) << report;
    EXPECT_NE(report.find("\"segments\": 1"), std::string::npos) << report;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(report, m, std::regex("\"depth_aligned\": ([0-9]+)"))) << report;
    EXPECT_GE(std::stoi(m[1]), 15) << "the covered frames, by the depth";
    const double ate = ateOf(run.output);
    EXPECT_GT(ate, 0) << run.output;
    EXPECT_LT(ate, 0.03) << run.output;
}

TEST(CameraOnlySlam, VoLostWithNothingToRelocalizeOnStartsANewSegmentOrIsBridged) {
    lodestone::test::TempDir dir;
    const std::string rawlog = cameraOnlyOffice(dir, 150, 170);
    // Relocalization and bridging off (the depth's too): the restart frame begins a second
    // segment, tracking goes on.
    const auto run = lodestone::test::runCommand(
        kSlam + " --rawlog " + rawlog + " --config " +
        rgbdOnlyWith(dir.file("segment.ini"), {{"relocalize_keyframes", "0"},
                                               {"bridge_max_seconds", "0"},
                                               {"bridge_by_depth", "false"},
                                               {"bridge_turn_by_depth", "false"}}) +
        " --out " +
        dir.file("out") + " --quiet");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string report = reportOf(dir.file("out"));
    EXPECT_NE(report.find("\"vo_gaps\": 1"), std::string::npos) << report;
    EXPECT_NE(report.find("\"segments\": 2"), std::string::npos) << report;
    // The segment's record: tracking lost after the last frame before the cover (frame 149 of
    // 15 Hz), found again at frame 170.
    std::smatch m;
    ASSERT_TRUE(std::regex_search(report, m,
                                  std::regex("\"lift_time\": ([0-9.e+]+),\\s*\"put_down_time\": ([0-9.e+]+)")))
        << report;
    EXPECT_NEAR(std::stod(m[2]) - std::stod(m[1]), 21.0 / 15.0, 0.1);
    const auto traj = lodestone::io::readTumTrajectory(dir.file("out/trajectory.tum"));
    ASSERT_FALSE(traj.empty());
    EXPECT_GT(traj.back().timestamp - traj.front().timestamp, 20.0);

    // With bridging on for gaps up to 2 s, the same 1.3 s gap is bridged: one segment.
    const auto bridged = lodestone::test::runCommand(
        kSlam + " --rawlog " + rawlog + " --config " +
        rgbdOnlyWith(dir.file("bridge.ini"), {{"relocalize_keyframes", "0"},
                                              {"bridge_max_seconds", "2.0"},
                                              {"bridge_by_depth", "false"},
                                              {"bridge_turn_by_depth", "false"}}) +
        " --out " + dir.file("bridged") + " --quiet");
    ASSERT_EQ(bridged.exitCode, 0) << bridged.output;
    const std::string report2 = reportOf(dir.file("bridged"));
    EXPECT_NE(report2.find("\"vo_gaps_bridged\": 1"), std::string::npos) << report2;
    EXPECT_NE(report2.find("\"segments\": 1"), std::string::npos) << report2;

    // The depth's bridges as rgbd_only.ini ships them (no gyro recorded): the gap's frames hold
    // no depth, but the restart frame's aligns with the last tracked frame's across it - the
    // ICP started where the cruise puts the camera - and measures its turn: one segment, the
    // map as good as with no gap (0.0054 m, measured; with the velocity fading to rest the
    // alignment was not found and a second segment began).
    const auto byDepth = lodestone::test::runCommand(
        kSlam + " --rawlog " + rawlog + " --config " +
        rgbdOnlyWith(dir.file("depth.ini"), {{"relocalize_keyframes", "0"}, {"bridge_max_seconds", "0"}}) +
        " --out " + dir.file("depth") + " --ground-truth " + dir.file("camera.gt.tum") + " --quiet");
    ASSERT_EQ(byDepth.exitCode, 0) << byDepth.output;
    const std::string report3 = reportOf(dir.file("depth"));
    EXPECT_NE(report3.find("\"vo_gaps_bridged_by_depth_turn\": 1"), std::string::npos) << report3;
    EXPECT_NE(report3.find("\"segments\": 1"), std::string::npos) << report3;
    const double ate = ateOf(byDepth.output);
    EXPECT_GT(ate, 0) << byDepth.output;
    EXPECT_LT(ate, 0.01) << byDepth.output;
}

// A hand-held recording with a gyro, run with rgbd_only.ini as shipped (use_gyro: a gyro where
// one is recorded): the gyro's rotation reaches VO on every frame that has a reference, and the
// run is as good as without it.
TEST(CameraOnlySlam, AHandHeldImuReachesTheOdometryAndTheGraph) {
    lodestone::test::TempDir dir;
    ASSERT_TRUE(handHeldOfficeWithImu(dir));
    const auto run = lodestone::test::runCommand(
        kSlam + " --rawlog " + dir.file("hand.rawlog") + " --config " + kConfigDir +
        "/slam/rgbd_only.ini --out " + dir.file("out") + " --ground-truth " + dir.file("hand.gt.tum") +
        " --quiet");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string report = reportOf(dir.file("out"));
    std::smatch m;
    ASSERT_TRUE(std::regex_search(report, m, std::regex("\"frames_with_gyro_rotation\": ([0-9]+)")))
        << report;
    EXPECT_GT(std::stoi(m[1]), 400) << "the office's 428 frames, all but VO's first";
    EXPECT_NE(report.find("\"gyro_label\": \"IMU\""), std::string::npos);
    // The same IMU's accelerometer: an up for every node after VO's first 1.3 s (the window and
    // the velocities at its ends), each a prior the optimizer holds - and, the floor as a
    // landmark on (as rgbd_only.ini ships), VO's first nodes where the floor is in view.
    std::smatch ups, priors, nodes;
    ASSERT_TRUE(std::regex_search(report, ups, std::regex("\"nodes_with_measured_up\": ([0-9]+)")));
    ASSERT_TRUE(std::regex_search(report, priors, std::regex("\"attitude_priors\": ([0-9]+)")));
    ASSERT_TRUE(std::regex_search(run.output, nodes, std::regex("([0-9]+) nodes")));
    EXPECT_GT(std::stoi(ups[1]), 0.8 * std::stoi(nodes[1])) << report;
    EXPECT_GE(std::stoi(priors[1]), std::stoi(ups[1])) << "each measured up held";
    EXPECT_LE(std::stoi(priors[1]), std::stoi(ups[1]) + countIn(report, "nodes_with_floor_up"))
        << "the others the floor's";
    EXPECT_LE(std::stoi(priors[1]), std::stoi(nodes[1]));
    const double ate = ateOf(run.output);
    EXPECT_GT(ate, 0) << run.output;
    EXPECT_LT(ate, 0.03) << run.output;
}

// A 6 s gap (the lens covered, no depth, nothing to relocalize on) that a gyro covers: bridged by
// the gyro's rotation and the fading velocity - one segment, the turn across the gap the truth's;
// a gap longer than gyro_bridge_max_seconds still opens a segment.
TEST(CameraOnlySlam, AGapTheGyroCoversIsBridgedByIt) {
    lodestone::test::TempDir dir;
    const int from = 150, to = 240;  // 15 Hz: 6 s
    const std::string rawlog = cameraOnlyOffice(dir, from, to, false, "--handheld --gyro");
    const auto runWith = [&](const std::string& name, const std::string& maxSeconds) {
        const auto run = lodestone::test::runCommand(
            kSlam + " --rawlog " + rawlog + " --config " +
            rgbdOnlyWith(dir.file(name + ".ini"), {{"relocalize_keyframes", "0"},
                                                   {"bridge_max_seconds", "0"},
                                                   {"use_gyro", "true"},
                                                   {"gyro_bridge_max_seconds", maxSeconds}}) +
            " --out " + dir.file(name) + " --ground-truth " + dir.file("camera.gt.tum") + " --quiet");
        EXPECT_EQ(run.exitCode, 0) << run.output;
        return reportOf(dir.file(name));
    };
    const std::string report = runWith("gyro", "10");
    EXPECT_NE(report.find("\"vo_gaps\": 1"), std::string::npos) << report;
    EXPECT_NE(report.find("\"vo_gaps_bridged_by_gyro\": 1"), std::string::npos) << report;
    EXPECT_NE(report.find("\"segments\": 1"), std::string::npos) << report;
    // Across the gap, the estimate turned as the camera did (the gyro's 0.1 deg/s bias over 6 s
    // and VO's own error on either side: within 2 deg).
    const auto est = lodestone::io::readTumTrajectory(dir.file("gyro/trajectory.tum"));
    const auto gt = lodestone::io::readTumTrajectory(dir.file("camera.gt.tum"));
    ASSERT_FALSE(est.empty());
    const double t0 = gt.front().timestamp;
    const auto* a = lodestone::io::poseNearest(est, t0 + (from - 2) / 15.0, 0.5);
    const auto* b = lodestone::io::poseNearest(est, t0 + (to + 2) / 15.0, 0.5);
    ASSERT_TRUE(a && b);
    const auto* ga = lodestone::io::poseNearest(gt, a->timestamp, 0.01);
    const auto* gb = lodestone::io::poseNearest(gt, b->timestamp, 0.01);
    ASSERT_TRUE(ga && gb);
    const mrpt::poses::CPose3D turned = b->pose - a->pose, truth = gb->pose - ga->pose;
    const Eigen::Matrix3d dR = turned.getRotationMatrix().asEigen().transpose() *
                               truth.getRotationMatrix().asEigen();
    EXPECT_GT(Eigen::AngleAxisd(truth.getRotationMatrix().asEigen()).angle(), 0.05)
        << "the camera turns across the gap";
    EXPECT_LT(Eigen::AngleAxisd(dR).angle(), 2 * M_PI / 180);

    const std::string shorter = runWith("short", "2");
    EXPECT_NE(shorter.find("\"vo_gaps_bridged_by_gyro\": 0"), std::string::npos) << shorter;
    EXPECT_NE(shorter.find("\"segments\": 2"), std::string::npos) << shorter;
}

