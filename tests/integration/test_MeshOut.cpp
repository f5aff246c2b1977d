// lodestone-slam --mesh as a user runs it: the bundled rawlog's run gets mesh.ply; a run with
// no usable depth writes none and says why; [dense] typos stop the run before any work.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

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
