// lodestone-slam --mesh as a user runs it: the bundled rawlog's run gets mesh.ply, after the run
// or fused as it goes; a run with no usable depth writes none and says why; [dense] typos stop
// the run before any work.
#include <gtest/gtest.h>

#include <lodestone/dense/Mesh.h>

#include <Eigen/Core>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "MeshCompare.h"
#include "StockTools.h"
#include "TestPaths.h"

namespace {
namespace fs = std::filesystem;
const std::string kSlam = LODESTONE_SLAM_BINARY;
const std::string kConfigDir = LODESTONE_CONFIG_INI_DIR;
const std::string kOfficeRawlog = LODESTONE_OFFICE_RAWLOG;
}  // namespace

TEST(MeshOut, TheBundledRunGetsItsDenseModel) {
    lodestone::test::TempDir dir;
    const auto r = lodestone::test::runCommand(kSlam + " --rawlog " + kOfficeRawlog + " --config " + kConfigDir +
                                               "/slam/slam.ini --quiet --mesh --out " + dir.path().string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ASSERT_TRUE(fs::exists(dir.file("mesh.ply"))) << r.output;
    const std::string report = lodestone::test::readTextFile(dir.file("report.json"));
    EXPECT_NE(report.find("\"written\": true"), std::string::npos) << report;
    const std::string mesh = lodestone::test::readTextFile(dir.file("mesh.ply"));
    EXPECT_NE(mesh.find("element face "), std::string::npos);
    EXPECT_GT(mesh.size(), 1000000u);  // (hundreds of thousands of triangles)
}

TEST(MeshOut, ARunWithoutUsableDepthWritesNoMeshAndSaysWhy) {
    // Depth fused only from 0.30 to 0.35 m: nothing in the office is that near.
    lodestone::test::TempDir dir;
    std::ofstream(dir.file("slam.ini")) << lodestone::test::readTextFile(kConfigDir + "/slam/slam.ini")
                                        << "\n[dense]\nmin_depth = 0.30\nmax_depth = 0.35\n";
    const auto r = lodestone::test::runCommand(kSlam + " --rawlog " + kOfficeRawlog + " --config " + dir.file("slam.ini") +
                                               " --quiet --mesh --out " + dir.path().string());
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_FALSE(fs::exists(dir.file("mesh.ply")));
    EXPECT_NE(r.output.find("--mesh: no mesh.ply: no keyframe's frame had usable depth"), std::string::npos) << r.output;
    EXPECT_NE(lodestone::test::readTextFile(dir.file("report.json")).find("\"written\": false"), std::string::npos);
}

TEST(MeshOut, ATypoInTheDenseSectionStopsTheRunBeforeAnyWork) {
    lodestone::test::TempDir dir;
    std::ofstream(dir.file("slam.ini")) << lodestone::test::readTextFile(kConfigDir + "/slam/slam.ini")
                                        << "\n[dense]\nvoxel_sise = 0.02\n";
    const auto r = lodestone::test::runCommand(kSlam + " --rawlog " + kOfficeRawlog + " --config " + dir.file("slam.ini") +
                                               " --quiet --mesh --out " + dir.file("out"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("voxel_sise"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.file("out/trajectory.tum")));
}

namespace {

std::vector<Eigen::Vector3f> plyVertices(const std::string& path) {
    return lodestone::dense::readMeshPly(path).vertices;
}

}  // namespace

TEST(MeshOut, FusedWhileTheRunGoesTheModelIsTheOneFusedAfterIt) {
    // Keyframes fused as they are made and re-fused where the graph moved them more than half a
    // voxel at the farthest fused depth: the same model as the pass after the run, but for those
    // small moves.
    lodestone::test::TempDir dir;
    std::ofstream(dir.file("slam.ini")) << lodestone::test::readTextFile(kConfigDir + "/slam/slam.ini")
                                        << "\n[dense]\nfusion = while_running\n";
    const auto running = lodestone::test::runCommand(kSlam + " --rawlog " + kOfficeRawlog + " --config " +
                                                     dir.file("slam.ini") + " --quiet --mesh --out " + dir.file("running"));
    ASSERT_EQ(running.exitCode, 0) << running.output;
    const auto after = lodestone::test::runCommand(kSlam + " --rawlog " + kOfficeRawlog + " --config " + kConfigDir +
                                                   "/slam/slam.ini --quiet --mesh --out " + dir.file("after"));
    ASSERT_EQ(after.exitCode, 0) << after.output;
    const std::string report = lodestone::test::readTextFile(dir.file("running/report.json"));
    EXPECT_NE(report.find("\"fusion\": \"while_running\""), std::string::npos) << report;
    EXPECT_NE(report.find("\"written\": true"), std::string::npos) << report;
    EXPECT_FALSE(fs::exists(dir.file("running/mesh.ply.frames")));  // the frame store is gone
    const auto a = plyVertices(dir.file("running/mesh.ply")), b = plyVertices(dir.file("after/mesh.ply"));
    ASSERT_GT(b.size(), 100000u);
    EXPECT_NEAR(double(a.size()), double(b.size()), 0.05 * double(b.size()));
    EXPECT_GT(lodestone::test::shareWithin(b, a, 0.005f), 0.95);
    EXPECT_GT(lodestone::test::shareWithin(a, b, 0.005f), 0.95);
}

TEST(MeshOut, AFinishedRunsFolderGetsItsDenseModelFromItsRawlog) {
    // lodestone-inspect mesh: the run's keyframes (nodes.csv) at its optimized poses
    // (trajectory.tum) - the model lodestone-slam --mesh makes, up to the TUM file's digits.
    lodestone::test::TempDir dir;
    const auto run = lodestone::test::runCommand(kSlam + " --rawlog " + kOfficeRawlog + " --config " + kConfigDir +
                                                 "/slam/slam.ini --quiet --mesh --out " + dir.file("run"));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string inspect = LODESTONE_INSPECT_BINARY;
    const auto r = lodestone::test::runCommand(inspect + " mesh " + dir.file("run") + " --rawlog " + kOfficeRawlog +
                                               " --out " + dir.file("again.ply"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("from 24 of 24 keyframes"), std::string::npos) << r.output;
    const auto a = plyVertices(dir.file("run/mesh.ply")), b = plyVertices(dir.file("again.ply"));
    EXPECT_GT(lodestone::test::shareWithin(a, b, 0.002f), 0.99);
    EXPECT_GT(lodestone::test::shareWithin(b, a, 0.002f), 0.99);
    // Another rawlog than the run's is named.
    const std::string other = kConfigDir + "/slam/slam.ini";
    const auto bad = lodestone::test::runCommand(inspect + " mesh " + dir.file("run") + " --rawlog " + other);
    EXPECT_EQ(bad.exitCode, 1) << bad.output;
    EXPECT_NE(bad.output.find(other), std::string::npos) << bad.output;
}

TEST(MeshOut, ASavedMapGetsItsDenseModelFromItsSessionsRawlog) {
    lodestone::test::TempDir dir;
    const auto run = lodestone::test::runCommand(kSlam + " --rawlog " + kOfficeRawlog + " --config " + kConfigDir +
                                                 "/slam/slam.ini --quiet --mesh --out " + dir.file("run") +
                                                 " --map-out " + dir.file("map"));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string inspect = LODESTONE_INSPECT_BINARY;
    const auto r = lodestone::test::runCommand(inspect + " mesh " + dir.file("map") + " --rawlog " + kOfficeRawlog);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ASSERT_TRUE(fs::exists(dir.file("map/mesh.ply"))) << r.output;
    // The map's poses are the run's: the same model.
    EXPECT_GT(lodestone::test::shareWithin(plyVertices(dir.file("run/mesh.ply")), plyVertices(dir.file("map/mesh.ply")),
                                           0.002f),
              0.99);
    // The map still reads, with its model beside it; a session it does not have is named.
    EXPECT_EQ(lodestone::test::runCommand(inspect + " map " + dir.file("map")).exitCode, 0);
    const auto bad =
        lodestone::test::runCommand(inspect + " mesh " + dir.file("map") + " --rawlog " + kOfficeRawlog + " --session 3");
    EXPECT_EQ(bad.exitCode, 1) << bad.output;
    EXPECT_NE(bad.output.find("no keyframe in session 3 of 1"), std::string::npos) << bad.output;
}

TEST(MeshOut, AFrameStoreThatCannotBeWrittenCostsTheMeshNotTheRun) {
    lodestone::test::TempDir dir;
    std::ofstream(dir.file("slam.ini")) << lodestone::test::readTextFile(kConfigDir + "/slam/slam.ini")
                                        << "\n[dense]\nfusion = while_running\n";
    fs::create_directories(dir.file("out/mesh.ply.frames"));  // (a folder where the store's file goes)
    const auto r = lodestone::test::runCommand(kSlam + " --rawlog " + kOfficeRawlog + " --config " + dir.file("slam.ini") +
                                               " --quiet --mesh --out " + dir.file("out"));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir.file("out/trajectory.tum")));
    EXPECT_FALSE(fs::exists(dir.file("out/mesh.ply")));
    EXPECT_NE(r.output.find("mesh.ply.frames: the dense model's frame store cannot be written"), std::string::npos)
        << r.output;
}
