// lodestone-slam --map-out: the map a run leaves, described by lodestone-inspect map; its own
// folder (never --out's); a map that cannot be written costs none of the run's other outputs.
#include <gtest/gtest.h>
#include <lodestone/datasets/MagneticRecordingImport.h>
#include <lodestone/maps/SavedMap.h>
#include <lodestone/obs/registerAllClasses.h>

#include <filesystem>
#include <fstream>

#include "StockTools.h"
#include "TestPaths.h"

namespace {
const std::string kSlam = LODESTONE_SLAM_BINARY;
const std::string kInspect = LODESTONE_INSPECT_BINARY;
const std::string kConfig = std::string(LODESTONE_CONFIG_INI_DIR) + "/slam/magnetic_window.ini";

/** Two laps of a 3 m x 2 m rectangle at 0.5 m/s, 10 Hz, through a field with a few bumps. */
lodestone::datasets::MagneticRecording twoLaps() {
    lodestone::datasets::MagneticRecording rec;
    rec.name = "two laps";
    const double corners[5][2] = {{0, 0}, {3, 0}, {3, 2}, {0, 2}, {0, 0}};
    double t = 0, heading = 0;
    for (int lap = 0; lap < 2; ++lap) {
        for (int side = 0; side < 4; ++side) {
            const double dx = corners[side + 1][0] - corners[side][0];
            const double dy = corners[side + 1][1] - corners[side][1];
            const double len = std::hypot(dx, dy);
            heading += std::remainder(std::atan2(dy, dx) - heading, 2 * M_PI);
            for (double s = 0; s < len; s += 0.05, t += 0.1) {
                const double x = corners[side][0] + dx * s / len, y = corners[side][1] + dy * s / len;
                const double bump = 10 * std::exp(-((x - 1) * (x - 1) + y * y) / 0.2) +
                                    8 * std::exp(-((x - 3) * (x - 3) + (y - 1) * (y - 1)) / 0.1);
                const double bx = 15 + bump, by = -bump, bz = -45 + 0.5 * bump;
                const double c = std::cos(heading), sn = std::sin(heading);
                rec.samples.push_back({t, x, y, heading, {c * bx + sn * by, -sn * bx + c * by, bz}});
            }
        }
    }
    return rec;
}
}  // namespace

TEST(MapOut, ARunLeavesAMapThatInspectDescribes) {
    lodestone::registerAllClasses();
    lodestone::test::TempDir dir;
    lodestone::datasets::writeMagneticRecording(twoLaps(), dir.file("laps.rawlog"), {});
    const auto run = lodestone::test::runCommand(kSlam + " --rawlog " + dir.file("laps.rawlog") +
                                                 " --config " + kConfig + " --quiet --out " +
                                                 dir.file("out") + " --map-out " + dir.file("map"));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const auto map = lodestone::maps::readMap(dir.file("map"));
    std::ifstream trajectory(dir.file("out") + "/trajectory.tum");
    std::size_t lines = 0;
    for (std::string line; std::getline(trajectory, line);) lines += !line.empty() && line[0] != '#';
    EXPECT_EQ(map.nodes.size(), lines);  // every node of the run
    EXPECT_GT(map.manifest.magneticReadings, 0u);
    EXPECT_EQ(map.manifest.edgeDecider, "CompositeERD");
    const auto inspect = lodestone::test::runCommand(kInspect + " map " + dir.file("map"));
    EXPECT_EQ(inspect.exitCode, 0) << inspect.output;
    EXPECT_NE(inspect.output.find("nodes " + std::to_string(map.nodes.size())), std::string::npos)
        << inspect.output;
    EXPECT_NE(inspect.output.find("magnetometers: MAG"), std::string::npos) << inspect.output;
    // A map that cannot be written (its folder's parent is a file): exit 1 naming it, and the
    // run's outputs are all there.
    std::ofstream(dir.file("a_file")) << "x";
    const auto bad = lodestone::test::runCommand(
        kSlam + " --rawlog " + dir.file("laps.rawlog") + " --config " + kConfig +
        " --quiet --out " + dir.file("out2") + " --map-out " + dir.file("a_file") + "/map");
    EXPECT_EQ(bad.exitCode, 1) << bad.output;
    EXPECT_NE(bad.output.find("a_file/map"), std::string::npos) << bad.output;
    EXPECT_TRUE(std::filesystem::exists(dir.file("out2") + "/trajectory.tum"));
    EXPECT_TRUE(std::filesystem::exists(dir.file("out2") + "/report.json"));
    // --map-out must not be --out.
    const auto same = lodestone::test::runCommand(kSlam + " --rawlog " + dir.file("laps.rawlog") +
                                                  " --config " + kConfig + " --quiet --out " +
                                                  dir.file("out3") + " --map-out " + dir.file("out3"));
    EXPECT_EQ(same.exitCode, 2) << same.output;
    // A folder that is not a map.
    const auto notMap = lodestone::test::runCommand(kInspect + " map " + dir.file("out"));
    EXPECT_EQ(notMap.exitCode, 1) << notMap.output;
    EXPECT_NE(notMap.output.find("manifest.ini"), std::string::npos) << notMap.output;
}
