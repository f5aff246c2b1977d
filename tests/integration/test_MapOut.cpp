// lodestone-slam --map-out: the map a run leaves, described by lodestone-inspect map; its own
// folder (never --out's); a map that cannot be written costs none of the run's other outputs.
// --map-in: a later run relocalizes in the map and tracks against it without moving it; a map
// from other deciders or a damaged one is refused before any work.
#include <gtest/gtest.h>
#include <lodestone/datasets/MagneticRecordingImport.h>
#include <lodestone/maps/SavedMap.h>
#include <lodestone/obs/registerAllClasses.h>

#include <lodestone/io/RawlogSource.h>
#include <lodestone/io/RawlogWriter.h>
#include <lodestone/io/TumTrajectory.h>
#include <mrpt/graphs/CNetworkOfPoses.h>
#include <opencv2/imgcodecs.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "StockTools.h"
#include "TestPaths.h"

namespace {
const std::string kSlam = LODESTONE_SLAM_BINARY;
const std::string kInspect = LODESTONE_INSPECT_BINARY;
const std::string kConfig = std::string(LODESTONE_CONFIG_INI_DIR) + "/slam/magnetic_window.ini";

std::string slurp(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

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
/** twoLaps() recorded as DIR/NAME.rawlog with the drift model of `seed`. */
std::string recordLaps(const lodestone::test::TempDir& dir, const std::string& name, int seed) {
    lodestone::datasets::OdometryDriftModel drift;
    drift.seed = static_cast<std::uint64_t>(seed);
    lodestone::datasets::writeMagneticRecording(twoLaps(), dir.file(name + ".rawlog"), drift);
    return dir.file(name + ".rawlog");
}

/** lodestone-slam with the window closer on `rawlog`, outputs in DIR/OUT, `extra` options. */
lodestone::test::CommandResult slamOn(const lodestone::test::TempDir& dir, const std::string& rawlog,
                                      const std::string& out, const std::string& extra) {
    return lodestone::test::runCommand(kSlam + " --rawlog " + rawlog + " --config " + kConfig +
                                       " --quiet --out " + dir.file(out) + " " + extra);
}
}  // namespace

TEST(MapOut, ARunLeavesAMapThatInspectDescribes) {
    lodestone::registerAllClasses();
    lodestone::test::TempDir dir;
    lodestone::datasets::writeMagneticRecording(twoLaps(), dir.file("laps.rawlog"), {});
    // (saved every 10 s of the 40 s as well: each time whole)
    const auto run = lodestone::test::runCommand(
        kSlam + " --rawlog " + dir.file("laps.rawlog") + " --config " + kConfig + " --quiet --out " +
        dir.file("out") + " --map-out " + dir.file("map") + " --map-every 10");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(slurp(dir.file("out") + "/report.json").find("\"saved_while_running\": 4"),
              std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(dir.file("map") + ".partial"));
    const auto map = lodestone::maps::readMap(dir.file("map"));
    std::ifstream trajectory(dir.file("out") + "/trajectory.tum");
    std::size_t lines = 0;
    for (std::string line; std::getline(trajectory, line);) lines += !line.empty() && line[0] != '#';
    EXPECT_EQ(map.nodes.size(), lines);  // every node of the run
    EXPECT_GT(map.manifest.magneticReadings, 0u);
    EXPECT_EQ(map.manifest.edgeDecider, "CompositeERD");
    const auto inspect = lodestone::test::runCommand(kInspect + " map " + dir.file("map") +
                                                     " --plot " + dir.file("map.png"));
    EXPECT_EQ(inspect.exitCode, 0) << inspect.output;
    const cv::Mat picture = cv::imread(dir.file("map.png"));
    ASSERT_FALSE(picture.empty());
    // The field was drawn: the picture holds more colours than a frame and a path do.
    std::set<std::uint32_t> colours;
    for (auto it = picture.begin<cv::Vec3b>(); it != picture.end<cv::Vec3b>(); ++it)
        colours.insert((*it)[0] << 16 | (*it)[1] << 8 | (*it)[2]);
    EXPECT_GT(colours.size(), 100u);
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

TEST(MapIn, ALaterRunRelocalizesInTheMapAndNeverMovesIt) {
    lodestone::registerAllClasses();
    lodestone::test::TempDir dir;
    ASSERT_EQ(slamOn(dir, recordLaps(dir, "first", 1), "first", "--map-out " + dir.file("map")).exitCode, 0);
    const auto map = lodestone::maps::readMap(dir.file("map"));
    const auto run = slamOn(dir, recordLaps(dir, "second", 2), "second",
                            "--map-in " + dir.file("map") + " --ground-truth " +
                                dir.file("second.gt.tum"));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string report = slurp(dir.file("second") + "/report.json");
    EXPECT_NE(report.find("\"relocations\": 1"), std::string::npos) << report.substr(0, 600);
    EXPECT_NE(report.find("\"map_nodes\": " + std::to_string(map.nodes.size())), std::string::npos);
    // The map's nodes are where the map put them.
    lodestone::graphslam::Graph after;
    after.loadFromTextFile(dir.file("second") + "/graph.graph");
    for (const auto& [id, pose] : map.graph.nodes) {
        ASSERT_TRUE(after.nodes.count(id));
        EXPECT_NEAR(after.nodes.at(id).x(), pose.x(), 1e-5) << id;
        EXPECT_NEAR(after.nodes.at(id).y(), pose.y(), 1e-5) << id;
    }
    // The trajectory is the run's own nodes on the map, with an ATE.
    const auto trajectory = lodestone::io::readTumTrajectory(dir.file("second") + "/trajectory.tum");
    EXPECT_GT(trajectory.size(), 50u);
    EXPECT_LT(trajectory.size(), after.nodes.size() - map.nodes.size() + 1);
    EXPECT_NE(run.output.find("ATE RMSE"), std::string::npos) << run.output;
}

/** A room's field: the earth's and a few bumps a few decimetres wide over a 3 m square. */
Eigen::Vector3d roomField(double x, double y) {
    const double bumps[7][6] = {{0.5, 0.6, 0.3, 9, -4, 3},  {1.6, 0.4, 0.25, -7, 6, -5},
                                {2.5, 1.2, 0.35, 5, 8, 4},   {1.2, 1.6, 0.3, -6, -7, 6},
                                {0.4, 2.4, 0.25, 8, 3, -6},  {2.2, 2.6, 0.3, -5, -6, -4},
                                {1.5, 2.9, 0.2, 6, -3, 5}};
    Eigen::Vector3d b(15, 0, -45);
    for (const auto& k : bumps) {
        const double g = std::exp(-((x - k[0]) * (x - k[0]) + (y - k[1]) * (y - k[1])) / (2 * k[2] * k[2]));
        b += g * Eigen::Vector3d(k[3], k[4], k[5]);
    }
    return b;
}

/** A walk through `corners` at 0.5 m/s, 10 Hz, reading roomField in the walker's frame. */
lodestone::datasets::MagneticRecording walkThroughRoom(const std::vector<Eigen::Vector2d>& corners) {
    lodestone::datasets::MagneticRecording rec;
    rec.name = "room walk";
    double t = 0, heading = 0;
    for (std::size_t k = 0; k + 1 < corners.size(); ++k) {
        const Eigen::Vector2d d = corners[k + 1] - corners[k];
        heading += std::remainder(std::atan2(d.y(), d.x()) - heading, 2 * M_PI);
        for (double s = 0; s < d.norm(); s += 0.05, t += 0.1) {
            const Eigen::Vector2d p = corners[k] + d * (s / d.norm());
            const Eigen::Vector3d b = roomField(p.x(), p.y());
            const double c = std::cos(heading), sn = std::sin(heading);
            rec.samples.push_back({t, p.x(), p.y(), heading, {c * b.x() + sn * b.y(), -sn * b.x() + c * b.y(), b.z()}});
        }
    }
    return rec;
}

TEST(MapIn, ARunThatOnlyCrossesTheMappedLinesRelocalizesInTheFieldMap) {
    // The map mows the room along x (lines 0.5 m apart); the later run crosses them on the
    // diagonals and never follows one, either way: the window closer has no line to compare,
    // the field map over the floor places it.
    lodestone::registerAllClasses();
    lodestone::test::TempDir dir;
    // The field map's localizer alone: the map run then has no closures and its map is the
    // exact odometry (the window closer has its own tests).
    std::string ini = slurp(kConfig);
    const auto children = ini.find("children =");
    ASSERT_NE(children, std::string::npos);
    ini.replace(children, ini.find('\n', children) - children, "children = MagneticFieldMapERD");
    std::ofstream(dir.file("field_map.ini")) << ini;
    const auto slamWith = [&](const std::string& rawlog, const std::string& out, const std::string& extra) {
        return lodestone::test::runCommand(kSlam + " --rawlog " + rawlog + " --config " +
                                           dir.file("field_map.ini") + " --quiet --out " + dir.file(out) +
                                           " " + extra);
    };
    std::vector<Eigen::Vector2d> mowing;
    for (int k = 0; k <= 6; ++k) {
        mowing.emplace_back(k % 2 ? 3.0 : 0.0, 0.5 * k);
        mowing.emplace_back(k % 2 ? 0.0 : 3.0, 0.5 * k);
    }
    lodestone::datasets::OdometryDriftModel exact;
    exact.bias = exact.sp2 = exact.sh2 = 0;  // the map's frame is the reference's
    lodestone::datasets::writeMagneticRecording(walkThroughRoom(mowing), dir.file("map.rawlog"), exact);
    ASSERT_EQ(slamWith(dir.file("map.rawlog"), "first", "--map-out " + dir.file("map")).exitCode, 0);
    lodestone::datasets::OdometryDriftModel drift;
    drift.seed = 2;
    const auto crossing = walkThroughRoom({{0.3, 0.2}, {2.8, 2.9}, {0.4, 2.7}, {2.6, 0.3}, {0.3, 1.4}});
    lodestone::datasets::writeMagneticRecording(crossing, dir.file("cross.rawlog"), drift);
    const auto run = slamWith(dir.file("cross.rawlog"), "cross", "--map-in " + dir.file("map"));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string report = slurp(dir.file("cross") + "/report.json");
    ASSERT_NE(report.find("\"relocations\": 1"), std::string::npos) << report.substr(0, 600);
    // Where the run's nodes on the map are, against the walk's reference (the map's frame).
    const auto onMap = lodestone::io::readTumTrajectory(dir.file("cross") + "/trajectory.tum");
    const auto truth = lodestone::io::readTumTrajectory(dir.file("cross.gt.tum"));
    ASSERT_GT(onMap.size(), 20u);
    std::size_t near = 0;
    for (const auto& p : onMap) {
        const auto it = std::min_element(truth.begin(), truth.end(), [&](const auto& a, const auto& b) {
            return std::abs(a.timestamp - p.timestamp) < std::abs(b.timestamp - p.timestamp);
        });
        near += std::hypot(p.pose.x() - it->pose.x(), p.pose.y() - it->pose.y()) < 0.3;
    }
    EXPECT_GT(double(near) / double(onMap.size()), 0.8) << near << " of " << onMap.size();

    // A map whose band would need more cells than the INI allows: no field map, the run goes
    // on without the localizer and says why.
    const auto cap = ini.find("grid_max_cells");
    ASSERT_NE(cap, std::string::npos);
    ini.replace(cap, ini.find('\n', cap) - cap, "grid_max_cells = 100");
    std::ofstream(dir.file("field_map.ini")) << ini;
    const auto capped = slamWith(dir.file("cross.rawlog"), "capped", "--map-in " + dir.file("map"));
    ASSERT_EQ(capped.exitCode, 0) << capped.output;
    const std::string cappedReport = slurp(dir.file("capped") + "/report.json");
    EXPECT_NE(cappedReport.find("\"relocations\": 0"), std::string::npos);
    EXPECT_NE(cappedReport.find("more than 100 cells"), std::string::npos);
}

TEST(MapIn, AForeignOrDamagedMapIsRefusedBeforeAnyWork) {
    lodestone::registerAllClasses();
    lodestone::test::TempDir dir;
    lodestone::datasets::writeMagneticRecording(twoLaps(), dir.file("laps.rawlog"), {});
    const std::string rawlog = " --rawlog " + dir.file("laps.rawlog") + " --quiet";
    ASSERT_EQ(lodestone::test::runCommand(kSlam + rawlog + " --config " + kConfig + " --out " +
                                          dir.file("first") + " --map-out " + dir.file("map"))
                  .exitCode,
              0);
    // Made with the window closer alone; this INI hosts the GP matcher beside it.
    const std::string gp = std::string(LODESTONE_CONFIG_INI_DIR) + "/slam/magnetic_only.ini";
    const auto foreign = lodestone::test::runCommand(kSlam + rawlog + " --config " + gp +
                                                     " --out " + dir.file("gp") + " --map-in " +
                                                     dir.file("map"));
    EXPECT_EQ(foreign.exitCode, 1) << foreign.output;
    EXPECT_NE(foreign.output.find("MagneticWindowERD"), std::string::npos) << foreign.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("gp") + "/trajectory.tum"));
    // The same walk with its magnetometer under another label: another sensor set, refused.
    {
        lodestone::io::RawlogSource in(dir.file("laps.rawlog"));
        lodestone::io::RawlogWriter out(dir.file("other.rawlog"));
        while (auto obs = in.next()) {
            if (obs->sensorLabel == "MAG") obs->sensorLabel = "OTHER_MAG";
            out.write(*obs);
        }
        out.close();
    }
    const auto otherSensor = lodestone::test::runCommand(
        kSlam + " --rawlog " + dir.file("other.rawlog") + " --quiet --config " + kConfig +
        " --out " + dir.file("other") + " --map-in " + dir.file("map"));
    EXPECT_EQ(otherSensor.exitCode, 1) << otherSensor.output;
    EXPECT_NE(otherSensor.output.find("OTHER_MAG"), std::string::npos) << otherSensor.output;
    EXPECT_NE(otherSensor.output.find("magnetometers MAG"), std::string::npos) << otherSensor.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("other") + "/trajectory.tum"));
    // A node file cut short: named, exit 1, nothing written.
    const std::string nodes = dir.file("map") + "/nodes.bin";
    std::filesystem::resize_file(nodes, std::filesystem::file_size(nodes) / 2);
    const auto damaged = lodestone::test::runCommand(kSlam + rawlog + " --config " + kConfig +
                                                     " --out " + dir.file("damaged") +
                                                     " --map-in " + dir.file("map"));
    EXPECT_EQ(damaged.exitCode, 1) << damaged.output;
    EXPECT_NE(damaged.output.find("nodes.bin"), std::string::npos) << damaged.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("damaged") + "/trajectory.tum"));
    // Extending needs somewhere to write the map.
    const auto extend = lodestone::test::runCommand(kSlam + rawlog + " --config " + kConfig +
                                                    " --out " + dir.file("x") + " --map-in " +
                                                    dir.file("map") + " --mode extend");
    EXPECT_EQ(extend.exitCode, 2) << extend.output;
}

TEST(MapIn, ExtendThenLocalizeInTheExtendedMap) {
    lodestone::registerAllClasses();
    lodestone::test::TempDir dir;
    ASSERT_EQ(slamOn(dir, recordLaps(dir, "first", 1), "first", "--map-out " + dir.file("map")).exitCode, 0);
    const auto map = lodestone::maps::readMap(dir.file("map"));
    // Extend: the run's nodes that joined the map are saved with it, as session 1.
    const auto extend = slamOn(dir, recordLaps(dir, "second", 2), "second",
                               "--map-in " + dir.file("map") + " --mode extend --map-out " +
                                   dir.file("map2"));
    ASSERT_EQ(extend.exitCode, 0) << extend.output;
    const auto extended = lodestone::maps::readMap(dir.file("map2"));
    EXPECT_EQ(extended.manifest.sessions, 2u);
    ASSERT_GT(extended.nodes.size(), map.nodes.size() + 50);
    EXPECT_EQ(extended.sessions.front(), 0u);
    EXPECT_EQ(extended.sessions.back(), 1u);
    // The old part is where it was, to the closures' corrections (small, here).
    double moved = 0;
    for (const auto& [id, pose] : map.graph.nodes) {
        const auto& p = extended.graph.nodes.at(id);
        moved = std::max(moved, std::hypot(p.x() - pose.x(), p.y() - pose.y()));
    }
    EXPECT_LT(moved, 0.5);
    // And a third run localizes in the extended map.
    const auto localize =
        slamOn(dir, recordLaps(dir, "third", 3), "third", "--map-in " + dir.file("map2"));
    ASSERT_EQ(localize.exitCode, 0) << localize.output;
    const std::string third = slurp(dir.file("third") + "/report.json");
    EXPECT_NE(third.find("\"relocations\": 1"), std::string::npos);
    // The extended map drove its rectangle four times: the window closer kept most of the later
    // passes' readings in windows only (map_thinning_radius), and relocalized all the same.
    const auto count = [&](const std::string& key) {
        const auto at = third.find("\"" + key + "\": ");
        return at == std::string::npos ? -1.0 : std::stod(third.substr(at + key.size() + 4));
    };
    EXPECT_GT(count("map_readings"), 0);
    EXPECT_GT(count("map_readings_thinned"), 0.25 * count("map_readings"));
    EXPECT_LT(count("map_readings_thinned"), 0.75 * count("map_readings"));
}
