// Camera-only SLAM held level: the carrier's up where no accelerometer measured it, the floor in
// view giving the nodes their up and height, a step the depth left loose held by the carrier's
// motion.
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

// Without an IMU, `carrier_tilt_sigma_deg` gives every node the carrier's level up (its robot
// frame's z) as a prior in the graph (and `carrier_height_sigma` its height on one floor);
// where the accelerometer measured a node's up, the measurement stays and the carrier's fills
// in only the nodes it left. (The floor as a landmark off, as it must be with a carrier's
// height: rgbd_only.ini ships it on.)
TEST(CameraOnlySlam, ACarriersLevelUpHoldsTheNodesNoAccelerometerMeasured) {
    lodestone::test::TempDir dir;
    ASSERT_TRUE(handHeldOfficeWithImu(dir));
    const auto runWith = [&](const std::string& name,
                             const std::vector<std::pair<std::string, std::string>>& keys) {
        return runHandHeld(dir, name, keys);
    };
    const auto [noImu, noImuNodes] = runWith(
        "no_imu", {{"use_gyro", "false"}, {"use_gravity", "false"}, {"floor_level", "false"},
                   {"carrier_tilt_sigma_deg", "5"}, {"carrier_height_sigma", "0.05"}});
    ASSERT_GT(noImuNodes, 50);
    EXPECT_EQ(countIn(noImu, "nodes_with_carrier_up"), noImuNodes) << noImu;
    EXPECT_EQ(countIn(noImu, "attitude_priors"), noImuNodes) << "each one held by the optimizer";
    EXPECT_EQ(countIn(noImu, "nodes_with_measured_up"), -1) << "no accelerometer used";
    EXPECT_NE(noImu.find("\"carrier_height_sigma\": 0.05"), std::string::npos) << "and their heights";

    const auto [imu, imuNodes] = runWith("imu", {{"floor_level", "false"}, {"carrier_tilt_sigma_deg", "5"}});
    const int measured = countIn(imu, "nodes_with_measured_up"),
              carried = countIn(imu, "nodes_with_carrier_up");
    EXPECT_GT(measured, 0.8 * imuNodes) << imu;
    EXPECT_GT(carried, 0) << "VO's first 1.3 s: no window for the accelerometer yet";
    EXPECT_EQ(measured + carried, imuNodes) << imu;
    EXPECT_EQ(countIn(imu, "attitude_priors"), imuNodes);

    const auto [off, offNodes] =
        runWith("off", {{"use_gyro", "false"}, {"use_gravity", "false"}, {"floor_level", "false"}});
    EXPECT_EQ(countIn(off, "nodes_with_carrier_up"), -1) << "0: no such prior";
    EXPECT_EQ(countIn(off, "attitude_priors"), 0) << off;
}

TEST(CameraOnlySlam, TheFloorInViewGivesTheNodesTheirUpAndHeight) {
    lodestone::test::TempDir dir;
    ASSERT_TRUE(handHeldOfficeWithImu(dir));
    const auto runWith = [&](const std::string& name,
                             const std::vector<std::pair<std::string, std::string>>& keys) {
        return runHandHeld(dir, name, keys);
    };
    const auto ate = [](const std::string& report) {
        std::smatch m;
        return std::regex_search(report, m, std::regex("\"rmse_m\": ([0-9.eE+-]+)"))
                   ? std::stod(m[1])
                   : -1.0;
    };
    // Without an IMU: the floor's up and height wherever the office's floor is in view.
    const auto [floor, floorNodes] = runWith(
        "floor", {{"use_gyro", "false"}, {"use_gravity", "false"}, {"floor_level", "true"}});
    ASSERT_GT(floorNodes, 50);
    const int ups = countIn(floor, "nodes_with_floor_up"),
              heights = countIn(floor, "nodes_with_floor_height");
    // (a small office at 320x240: the floor is in view from 3 m, the ceiling from 2.5; measured
    // 27 of 107 nodes, 8 of them with the floor's height)
    EXPECT_GT(ups, floorNodes / 5) << floor;
    EXPECT_GT(heights, 0) << floor;
    EXPECT_LE(heights, ups);
    EXPECT_EQ(countIn(floor, "attitude_priors"), ups) << "each one held by the optimizer";
    // Nothing here is level but the floor and the ceiling: what the gate refused (measured: one
    // fit, a wall's corner levelled 22 deg off) stays a rare exception.
    EXPECT_LE(countIn(floor, "level_surfaces_beyond_the_up_gate"), ups / 10) << floor;
    EXPECT_GT(ate(floor), 0);
    EXPECT_LT(ate(floor), 0.016) << "the office's target";
    // With the IMU: the floor's up fused with the accelerometer's, never at odds with it.
    const auto [imu, imuNodes] = runWith("imu", {{"floor_level", "true"}});
    EXPECT_EQ(countIn(imu, "nodes_whose_floor_and_accelerometer_disagreed"), 0) << imu;
    EXPECT_GT(countIn(imu, "nodes_with_floor_up"), 0) << imu;
    EXPECT_LT(ate(imu), 0.016);
    // A carrier's common height and the floor's are two levels: one graph holds one.
    const auto both = lodestone::test::runCommand(
        kSlam + " --rawlog " + dir.file("hand.rawlog") + " --config " +
        rgbdOnlyWith(dir.file("both.ini"),
                     {{"floor_level", "true"}, {"carrier_height_sigma", "0.05"}}) +
        " --out " + dir.file("both") + " --quiet");
    EXPECT_NE(both.exitCode, 0);
    EXPECT_NE(both.output.find("floor_level"), std::string::npos) << both.output;
}

namespace {
/** A room whose far wall is plain paint, as are its floor and ceiling (no lamps): the robot's
 * camera alone (with a gyro) drives 4 m at it, with posters on the side walls, and turns left
 * 1 m before it - there the view holds one plane and the floor, whose depth pins the distance
 * to the wall and the height but not a step along the wall. Returns the rawlog's path. */
std::string plainWallRun(const lodestone::test::TempDir& dir) {
    std::ofstream(dir.file("wall.ini")) << R"([scenario]
name       = plain_wall
seed       = 3
start_time = 1700000000
[world]
wall_height        = 2.6
texture_resolution = 200
floor              = plain
ceiling            = plain
lamp_spacing       = 1000
wall_1 = posters 0 0  6 0
wall_2 = plain   6 0  6 4
wall_3 = posters 6 4  0 4  0 0
[path]
waypoints = 1 2  5 2  5 3.2
laps      = 1
[robot]
speed         = 0.4
turn_rate_deg = 35
wheel_base    = 0.23
wheel_radius  = 0.035
radius        = 0.18
[camera]
label     = RGBD
rate      = 30
width     = 640
height    = 480
pose      = 0.10 0 0.45 0
rgb_noise = 2.0
)";
    const auto sim = lodestone::test::runCommand(kSim + " -c " + dir.file("wall.ini") + " -o " +
                                                 dir.file("wall.rawlog") +
                                                 " --camera 320x240@15 --embedded-images --camera-only --gyro");
    EXPECT_EQ(sim.exitCode, 0) << sim.output;
    return dir.file("wall.rawlog");
}

/** Each consecutive edge of a run's graph, but the restarts' (a lost edge): its loosest
 * translational sigma [m] and its time [s], by the first node. */
std::map<mrpt::graphs::TNodeID, std::pair<double, double>> edgeLooseness(const std::string& dir) {
    const auto stamps = nodeStamps(dir);
    mrpt::graphs::CNetworkOfPoses3DInf graph;
    graph.loadFromTextFile(dir + "/graph.graph");
    std::map<mrpt::graphs::TNodeID, std::pair<double, double>> edges;
    for (const auto& [id, t] : stamps) {
        const auto edge = graph.edges.find({id, id + 1});
        if (edge == graph.edges.end() || !stamps.count(id + 1)) continue;
        const Eigen::Matrix<double, 6, 6> info = edge->second.cov_inv.asEigen();
        const Eigen::Matrix3d cov = info.ldlt().solve(Eigen::Matrix<double, 6, 6>::Identity()).topLeftCorner<3, 3>();
        const double loosest = std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvalues().maxCoeff());
        if (loosest > 10) continue;  // (a restart: lost_edge_sigma, no motion claimed)
        edges[id] = {loosest, stamps.at(id + 1) - t};
    }
    return edges;
}
}  // namespace

// Where VO tracks by the depth alone at a plain wall, the steps along it are unmeasured: their
// edges a quarter of a metre loose and more (PointToPlaneIcp's unobserved sigma, shrunk only by
// the frames' chaining), so a graph slides those nodes along the wall at no cost. With
// step_motion_prior each edge is held by what the carrier can do in its time - the fading
// velocity's spread (bridge_speed_sigma 0.5 m/s, bridge_velocity_seconds 1 s) - and a gap's
// edge in its tracked part too: no edge looser than twice the model's variance over its time
// allows, the edges VO measured as they were.
TEST(CameraOnlySlam, AStepTheDepthLeftLooseIsHeldByTheCarriersMotion) {
    lodestone::test::TempDir dir;
    const std::string rawlog = plainWallRun(dir);
    const auto runWith = [&](const std::string& name, const char* prior) {
        const auto run = lodestone::test::runCommand(
            kSlam + " --rawlog " + rawlog + " --config " +
            rgbdOnlyWith(dir.file(name + ".ini"), {{"step_motion_prior", prior}}) + " --out " +
            dir.file(name) + " --quiet");
        EXPECT_EQ(run.exitCode, 0) << run.output;
        return edgeLooseness(dir.file(name));
    };
    const auto loose = runWith("off", "false"), held = runWith("on", "true");
    ASSERT_EQ(loose.size(), held.size()) << "the same frames, the same nodes";
    lodestone::odometry::FadingVelocity model;  // (rgbd_only.ini's bridge_* values)
    model.speedSigma = 0.5;
    model.correlationSeconds = 1.0;
    model.acrossSeconds = 0.25;
    int unmeasured = 0;
    for (const auto& [id, off] : loose) {
        const auto& [sigmaOff, seconds] = off;
        const double sigmaOn = held.at(id).first;
        const double bound = std::sqrt(2 * model.displacementVariances(seconds, model.speedSigma).maxCoeff());
        if (sigmaOff > bound) ++unmeasured;
        EXPECT_LE(sigmaOn, bound) << "edge " << id << " of " << seconds << " s (without: " << sigmaOff << ")";
        if (sigmaOff < 0.01) {
            EXPECT_NEAR(sigmaOn, sigmaOff, 0.1 * sigmaOff) << "edge " << id << ": measured";
        }
    }
    EXPECT_GE(unmeasured, 1) << "the plain wall leaves a step's edge looser than the carrier can move";
}
