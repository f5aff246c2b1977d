// Camera-only SLAM across stretches VO cannot track: restarts that carry the velocity on, the
// carrier's cruise, and the turn measured by the gap's own depth where no gyro is.
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

namespace {
constexpr int kStretchFrom = 150, kStretchTo = 195;  // 15 Hz: 3 s

/** The hand-held office with a gyro, frames kStretchFrom..kStretchTo a grey picture (one VO
 * gap) or each a new picture of noise (VO restarts on each and loses track again: a chain of
 * gaps), bridged by the gyro and the motion model alone (the gaps' depth left out), the
 * velocity fading towards rest or a cruise over `cruise` seconds: how far the graph's odometry
 * edges chain across the stretch, and the truth's distance between the same nodes. */
void officeStretch(bool noise, const char* cruise, double& estimated, double& truth) {
    lodestone::test::TempDir dir;
    const std::string rawlog =
        cameraOnlyOffice(dir, kStretchFrom, kStretchTo, true, "--handheld --gyro", noise);
    const auto run = lodestone::test::runCommand(
        kSlam + " --rawlog " + rawlog + " --config " +
        rgbdOnlyWith(dir.file("run.ini"), {{"relocalize_keyframes", "0"},
                                           {"bridge_max_seconds", "0"},
                                           {"depth_alignment", "false"},
                                           {"bridge_by_depth", "false"},
                                           {"bridge_turn_by_depth", "false"},
                                           {"bridge_cruise_seconds", cruise}}) +
        " --out " + dir.file("out") + " --quiet");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string report = reportOf(dir.file("out"));
    std::smatch gaps;
    ASSERT_TRUE(std::regex_search(report, gaps, std::regex("\"vo_gaps_bridged_by_gyro\": ([0-9]+)")));
    if (noise) {
        EXPECT_GE(std::stoi(gaps[1]), 5) << "a restart every 6 frames";
        std::smatch carried;
        ASSERT_TRUE(std::regex_search(report, carried, std::regex("\"vo_restarts_carrying_velocity\": ([0-9]+)")));
        EXPECT_GE(std::stoi(carried[1]), 4) << "each restart after the first gap's";
    } else {
        EXPECT_EQ(std::stoi(gaps[1]), 1) << report;
    }
    EXPECT_NE(report.find("\"segments\": 1"), std::string::npos) << report;
    // The graph's odometry edges chained across the stretch, against the truth.
    const auto stamps = nodeStamps(dir.file("out"));
    const double t0 = stamps.begin()->second;
    mrpt::graphs::TNodeID a = 0, b = 0;
    for (const auto& [id, t] : stamps) {
        if (t <= t0 + (kStretchFrom - 1) / 15.0) a = id;
        if (t >= t0 + kStretchTo / 15.0 && b == 0) b = id;
    }
    ASSERT_GT(b, a);
    mrpt::graphs::CNetworkOfPoses3DInf graph;
    graph.loadFromTextFile(dir.file("out/graph.graph"));
    mrpt::poses::CPose3D chained;
    for (auto id = a; id < b; ++id) {
        const auto edge = graph.edges.find({id, id + 1});
        ASSERT_NE(edge, graph.edges.end()) << id;
        chained = chained + edge->second.getPoseMean();
    }
    const auto gt = lodestone::io::readTumTrajectory(dir.file("camera.gt.tum"));
    const auto* ga = lodestone::io::poseNearest(gt, stamps.at(a), 0.01);
    const auto* gb = lodestone::io::poseNearest(gt, stamps.at(b), 0.01);
    ASSERT_TRUE(ga && gb);
    estimated = chained.translation().norm();
    truth = (gb->pose - ga->pose).translation().norm();
}
}  // namespace

// A 3 s stretch whose every frame is a new picture of noise, the depth still the office's: VO
// restarts on each (it has features) and loses track again five frames later, so the stretch
// is a chain of gaps of 0.4 s. With a gyro, each is bridged by its rotation and the fading
// velocity. Each restart starts its gap from the velocity the one before carried to it, so the
// chain goes as far as one gap over the whole stretch does (the same recording with a grey
// picture instead: no restart) - not, as from a standstill at every restart, two fifths as far
// (0.16 m against 0.41, measured).
TEST(CameraOnlySlam, RestartsInAStretchVoCannotTrackCarryTheVelocityOn) {
    double oneGap = 0, oneGapTruth = 0, chain = 0, chainTruth = 0;
    officeStretch(false, "0", oneGap, oneGapTruth);
    officeStretch(true, "0", chain, chainTruth);
    EXPECT_GT(oneGapTruth, 0.5) << "the hand walks on through the stretch";
    EXPECT_NEAR(chainTruth, oneGapTruth, 0.05) << "the same stretch, its ends the nearest nodes";
    // (the fading velocity over 3 s carries a third of a walk at constant speed: both short of
    // the truth alike)
    EXPECT_GT(oneGap, 0.2 * oneGapTruth);
    EXPECT_NEAR(chain, oneGap, 0.25 * oneGap) << "truth " << chainTruth;
}

// The same stretch with the velocity fading towards the hand's pace over the 10 s before
// (bridge_cruise_seconds; at the gyro's turn rate) rather than towards rest: walked about as far
// as the truth (1.40 m of 1.25, measured; fading to rest 0.41) - and again alike in one gap or in
// a chain of them.
TEST(CameraOnlySlam, AStretchVoCannotTrackIsWalkedAtTheCarriersCruise) {
    double oneGap = 0, oneGapTruth = 0, chain = 0, chainTruth = 0;
    officeStretch(false, "10", oneGap, oneGapTruth);
    officeStretch(true, "10", chain, chainTruth);
    EXPECT_GT(oneGapTruth, 0.5) << "the hand walks on through the stretch";
    EXPECT_NEAR(oneGap, oneGapTruth, 0.25 * oneGapTruth);
    EXPECT_NEAR(chain, oneGap, 0.15 * oneGap) << "truth " << chainTruth;
}

// No gyro recorded: a 6 s gap where the images hold nothing (VO's own depth alignment off, so
// it loses track) but the depth still sees the office - the gap's turn and translation are
// measured by its frames' depth (bridge_turn_by_depth, as rgbd_only.ini ships): one segment,
// the turn across the gap the truth's. Without it the same gap opens a second segment; and
// where the lens sees no depth either, nothing measures the turn: a gap, not a guess.
TEST(CameraOnlySlam, AGapNoGyroCoversIsBridgedByTheDepthsTurn) {
    lodestone::test::TempDir dir;
    const int from = 150, to = 240;  // 15 Hz: 6 s
    const std::string rawlog = cameraOnlyOffice(dir, from, to, true, "--handheld");
    const auto runWith = [&](const std::string& name, const std::string& turnByDepth) {
        const auto run = lodestone::test::runCommand(
            kSlam + " --rawlog " + rawlog + " --config " +
            rgbdOnlyWith(dir.file(name + ".ini"), {{"relocalize_keyframes", "0"},
                                                   {"bridge_max_seconds", "0"},
                                                   {"depth_alignment", "false"},
                                                   {"bridge_turn_by_depth", turnByDepth}}) +
            " --out " + dir.file(name) + " --ground-truth " + dir.file("camera.gt.tum") + " --quiet");
        EXPECT_EQ(run.exitCode, 0) << run.output;
        return reportOf(dir.file(name));
    };
    const std::string report = runWith("turn", "true");
    EXPECT_NE(report.find("\"frames_with_gyro_rotation\": 0"), std::string::npos) << "no gyro recorded";
    EXPECT_NE(report.find("\"vo_gaps\": 1"), std::string::npos) << report;
    EXPECT_NE(report.find("\"vo_gaps_bridged_by_depth_turn\": 1"), std::string::npos) << report;
    EXPECT_NE(report.find("\"segments\": 1"), std::string::npos) << report;
    // The edge across the gap (the one between nodes furthest apart in time) against the truth:
    // the hand turned about 90 deg and walked 1.4 m in it.
    auto stamps = nodeStamps(dir.file("turn"));
    mrpt::graphs::CNetworkOfPoses3DInf graph;
    graph.loadFromTextFile(dir.file("turn/graph.graph"));
    mrpt::graphs::TNodeID gapFrom = 0;
    double longest = 0;
    for (const auto& [ids, edge] : graph.edges) {
        if (ids.second != ids.first + 1 || !stamps.count(ids.first) || !stamps.count(ids.second)) continue;
        const double seconds = stamps[ids.second] - stamps[ids.first];
        if (seconds > longest) longest = seconds, gapFrom = ids.first;
    }
    EXPECT_GT(longest, 5.0);
    const auto gt = lodestone::io::readTumTrajectory(dir.file("camera.gt.tum"));
    const auto* ga = lodestone::io::poseNearest(gt, stamps[gapFrom], 0.01);
    const auto* gb = lodestone::io::poseNearest(gt, stamps[gapFrom + 1], 0.01);
    ASSERT_TRUE(ga && gb);
    const mrpt::poses::CPose3D edge = graph.edges.find({gapFrom, gapFrom + 1})->second.getPoseMean();
    const mrpt::poses::CPose3D truth = gb->pose - ga->pose;
    const Eigen::Matrix3d dR =
        edge.getRotationMatrix().asEigen().transpose() * truth.getRotationMatrix().asEigen();
    EXPECT_GT(Eigen::AngleAxisd(truth.getRotationMatrix().asEigen()).angle(), 1.0) << "the hand turns";
    // Measured: 2.6 deg off (the yaw 1.5 deg short of 91.5, the tilt within 2 deg) at this
    // 320x240 camera's 80 depth columns. A turn, not a guess: the fading turn rate alone is
    // tens of degrees off.
    EXPECT_LT(Eigen::AngleAxisd(dR).angle(), 8 * M_PI / 180) << edge << " against " << truth;
    EXPECT_LT((edge.translation() - truth.translation()).norm(), 0.2) << edge << " against " << truth;

    const std::string without = runWith("without", "false");
    EXPECT_NE(without.find("\"segments\": 2"), std::string::npos) << without;

    lodestone::test::TempDir blindDir;
    const std::string blind = cameraOnlyOffice(blindDir, from, to, false, "--handheld");
    const auto run = lodestone::test::runCommand(
        kSlam + " --rawlog " + blind + " --config " +
        rgbdOnlyWith(blindDir.file("blind.ini"), {{"relocalize_keyframes", "0"}, {"bridge_max_seconds", "0"}}) +
        " --out " + blindDir.file("blind") + " --quiet");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string blindReport = reportOf(blindDir.file("blind"));
    EXPECT_NE(blindReport.find("\"vo_gaps_bridged_by_depth_turn\": 0"), std::string::npos) << blindReport;
    EXPECT_NE(blindReport.find("\"segments\": 2"), std::string::npos) << blindReport;
}

