// lodestone-slam as a user runs it: on the simulator and on the bundled rawlog, its outputs
// exist and parse, and bad input is refused before any work (or, for a corrupt rawlog, what
// was processed is still written).
#include <lodestone/io/TumTrajectory.h>
#include <mrpt/graphs/CNetworkOfPoses.h>
#include <opencv2/imgcodecs.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "StockTools.h"
#include "TestPaths.h"

namespace {
namespace fs = std::filesystem;
const std::string kSlam = LODESTONE_SLAM_BINARY;
const std::string kConfigDir = LODESTONE_CONFIG_INI_DIR;
const std::string kOfficeRawlog = LODESTONE_OFFICE_RAWLOG;

double ateOf(const std::string& output) {
    std::smatch m;
    const std::regex re("ATE RMSE ([0-9.]+) m");
    return std::regex_search(output, m, re) ? std::stod(m[1]) : -1;
}

/** Every output is there and says the same number of nodes. */
void expectOutputsParse(const lodestone::test::TempDir& dir) {
    for (const char* f : {"trajectory.tum", "graph.graph", "map.ply", "report.json", "graph.png",
                          "nodes.csv"}) {
        EXPECT_TRUE(fs::exists(dir.file(f))) << f;
    }
    const auto traj = lodestone::io::readTumTrajectory(dir.file("trajectory.tum"));
    // nodes.csv: a header and a row per node, the engine time of each a number.
    std::ifstream nodes(dir.file("nodes.csv"));
    std::string row;
    std::getline(nodes, row);
    EXPECT_EQ(row, "node,timestamp,segment,keyframe,engine_ms");
    std::size_t rows = 0;
    while (std::getline(nodes, row)) {
        ++rows;
        const double ms = std::stod(row.substr(row.rfind(',') + 1));
        EXPECT_TRUE(ms >= 0) << row;
    }
    EXPECT_EQ(rows, traj.size());
    mrpt::graphs::CNetworkOfPoses3DInf graph;
    graph.loadFromTextFile(dir.file("graph.graph"));
    EXPECT_GT(traj.size(), 5u);
    EXPECT_EQ(graph.nodes.size(), traj.size());
    EXPECT_GE(graph.edges.size(), traj.size() - 1);  // the odometry chain, and closures
    const std::string report = lodestone::test::readTextFile(dir.file("report.json"));
    EXPECT_NE(report.find("\"nodes\": " + std::to_string(traj.size())), std::string::npos) << report;
    EXPECT_NE(report.find("\"node_ms_by_decile\""), std::string::npos);
    // PLY: the header's vertex count matches the binary body (15 bytes a point).
    const std::string ply = lodestone::test::readTextFile(dir.file("map.ply"));
    std::smatch m;
    ASSERT_TRUE(std::regex_search(ply, m, std::regex("element vertex ([0-9]+)\n")));
    const std::size_t body = ply.size() - (ply.find("end_header\n") + 11);
    EXPECT_EQ(body, std::stoul(m[1]) * 15);
    EXPECT_GT(std::stoul(m[1]), 1000u);
}
}  // namespace

TEST(SlamBinary, SimulatedOfficeOdometryOnly) {
    lodestone::test::TempDir dir;
    const auto r = lodestone::test::runCommand(
        kSlam + " --sim " + kConfigDir + "/scenarios/office.ini --config " + kConfigDir +
        "/slam/odometry_only.ini --max-seconds 8 --quiet --out " + dir.path().string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    expectOutputsParse(dir);
    EXPECT_TRUE(fs::exists(dir.file("ground_truth.tum")));
    EXPECT_TRUE(fs::exists(dir.file("trajectory.png")));
    const double ate = ateOf(r.output);
    EXPECT_GT(ate, 0) << r.output;
    EXPECT_LT(ate, 0.02) << r.output;  // measured 0.004 m over the whole office run
    EXPECT_NE(lodestone::test::readTextFile(dir.file("report.json")).find("\"rmse_m\""), std::string::npos);
}

TEST(SlamBinary, BundledRawlogWithGroundTruth) {
    lodestone::test::TempDir dir;
    const std::string gt = std::regex_replace(kOfficeRawlog, std::regex("rawlog.gz$"), "gt.tum");
    const auto r = lodestone::test::runCommand(kSlam + " --rawlog " + kOfficeRawlog +
                                               " --ground-truth " + gt + " --config " + kConfigDir +
                                               "/slam/slam.ini --out " + dir.path().string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    expectOutputsParse(dir);
    const double ate = ateOf(r.output);
    EXPECT_GT(ate, 0) << r.output;
    EXPECT_LT(ate, 0.05) << r.output;
    // Not a terminal: plain progress lines, no carriage returns.
    EXPECT_EQ(r.output.find('\r'), std::string::npos);
    EXPECT_NE(r.output.find("done "), std::string::npos) << r.output;
    // The sample has two magnetometers: |B| over the floor, colour only where readings were
    // placed (the rest of the map is grey).
    const cv::Mat3b field = cv::imread(dir.file("field_map.png"), cv::IMREAD_COLOR);
    ASSERT_FALSE(field.empty()) << "no field_map.png";
    int coloured = 0;
    for (const auto& p : field) coloured += !(p[0] == p[1] && p[1] == p[2]);
    EXPECT_GT(coloured, 20000);  // about 190 cells of 0.1 m, ~20 px across each
}

TEST(SlamBinary, ConfigurationMistakesStopBeforeAnyWork) {
    lodestone::test::TempDir dir;
    const auto runWith = [&](const std::string& ini) {
        std::ofstream(dir.file("bad.ini")) << ini;
        return lodestone::test::runCommand(kSlam + " --rawlog " + kOfficeRawlog + " --config " +
                                           dir.file("bad.ini") + " --out " + dir.file("out"));
    };
    auto r = runWith("[graphslam]\nnode_decider = FusedOdometryNDR\n");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("node_decider"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("FusedOdometryNDR"), std::string::npos) << r.output;
    r = runWith("[CeresGSO]\nrobust_los = huber\n");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("robust_los"), std::string::npos) << r.output;
    r = runWith("[CeresGS0]\nmode = planar\n");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("CeresGS0"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.file("out")));
    r = lodestone::test::runCommand(kSlam + " --rawlog " + kOfficeRawlog + " --config " +
                                    dir.file("missing.ini") + " --out " + dir.file("out"));
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("missing.ini"), std::string::npos) << r.output;
}

TEST(SlamBinary, ARawlogWithoutTheNeededObservationsIsRefused) {
    const std::string laserOnly =
        (lodestone::test::mrptDatasetsDir() / "2006-01ENE-21-SENA_Telecom Faculty_one_loop_only.rawlog")
            .string();
    if (!fs::exists(laserOnly)) GTEST_SKIP() << "MRPT's sample datasets are not installed";
    lodestone::test::TempDir dir;
    const auto r = lodestone::test::runCommand(kSlam + " --rawlog '" + laserOnly + "' --config " +
                                               kConfigDir + "/slam/slam.ini --out " + dir.file("out"));
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("no CObservation3DRangeScan"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.file("out")));
}

TEST(SlamBinary, ACorruptRawlogStopsAtTheFaultAndKeepsWhatWasProcessed) {
    lodestone::test::TempDir dir;
    {
        const std::string bytes = lodestone::test::readTextFile(kOfficeRawlog);
        std::ofstream(dir.file("cut.rawlog.gz"), std::ios::binary)
            .write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
    }
    const auto r = lodestone::test::runCommand(kSlam + " --rawlog " + dir.file("cut.rawlog.gz") +
                                               " --config " + kConfigDir +
                                               "/slam/slam.ini --quiet --out " + dir.file("out"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("cut.rawlog.gz"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("writing what was processed"), std::string::npos) << r.output;
    const auto traj = lodestone::io::readTumTrajectory(dir.file("out/trajectory.tum"));
    EXPECT_GT(traj.size(), 5u);
    EXPECT_NE(lodestone::test::readTextFile(dir.file("out/report.json")).find("\"error\""), std::string::npos);
}

TEST(SlamBinary, UsageErrors) {
    EXPECT_EQ(lodestone::test::runCommand(kSlam).exitCode, 2);
    const auto both = lodestone::test::runCommand(kSlam + " --rawlog a --sim b --config c --out d");
    EXPECT_EQ(both.exitCode, 2);
    EXPECT_NE(both.output.find("exactly one of --rawlog and --sim"), std::string::npos);
    EXPECT_EQ(lodestone::test::runCommand(kSlam + " --help").exitCode, 0);
    const auto ahead = lodestone::test::runCommand(kSlam + " --rawlog a --config c --out d --decode-ahead -1");
    EXPECT_EQ(ahead.exitCode, 2);
    EXPECT_NE(ahead.output.find("--decode-ahead"), std::string::npos) << ahead.output;
}

TEST(SlamBinary, MrptsGraphSlamToolReadsTheGraph) {
    if (lodestone::test::runCommand("command -v graph-slam").exitCode != 0) {
        GTEST_SKIP() << "MRPT's graph-slam (Debian mrpt-apps) is not installed";
    }
    lodestone::test::TempDir dir;
    const auto r = lodestone::test::runCommand(kSlam + " --rawlog " + kOfficeRawlog + " --config " +
                                               kConfigDir + "/slam/slam.ini --quiet --out " +
                                               dir.path().string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const auto nodes = lodestone::io::readTumTrajectory(dir.file("trajectory.tum")).size();
    const auto info = lodestone::test::runCommand("graph-slam --info --3d -i " + dir.file("graph.graph"));
    EXPECT_EQ(info.exitCode, 0) << info.output;
    EXPECT_NE(info.output.find("Nodes count (in VERTEX2/3 entries) : " + std::to_string(nodes)),
              std::string::npos)
        << info.output;
}

TEST(SlamBinary, DecodingAheadChangesNothingButTheTime) {
    // A rawlog whose colour images are PNG files beside it (the simulator's default), run with
    // the images decoded in the frame loop and on a second thread: the same outputs, byte for
    // byte.
    lodestone::test::TempDir dir;
    const auto sim = lodestone::test::runCommand(std::string(LODESTONE_SIM_BINARY) + " -c " +
                                                 kConfigDir + "/scenarios/office.ini -o " +
                                                 dir.file("office.rawlog") + " --camera 320x240@15");
    ASSERT_EQ(sim.exitCode, 0) << sim.output;
    ASSERT_TRUE(fs::is_directory(dir.file("office_Images")));  // external images indeed
    for (const char* ahead : {"0", "8"}) {
        const auto r = lodestone::test::runCommand(
            kSlam + " --rawlog " + dir.file("office.rawlog") + " --config " + kConfigDir +
            "/slam/slam.ini --quiet --decode-ahead " + ahead + " --out " + dir.file(std::string("ahead") + ahead));
        ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    for (const char* f : {"trajectory.tum", "graph.graph", "closures.csv"}) {
        const std::string inLoop = lodestone::test::readTextFile(dir.file(std::string("ahead0/") + f));
        EXPECT_GT(inLoop.size(), 100u) << f;
        EXPECT_EQ(inLoop, lodestone::test::readTextFile(dir.file(std::string("ahead8/") + f))) << f;
    }
    EXPECT_NE(lodestone::test::readTextFile(dir.file("ahead8/report.json")).find("\"decode_ahead\": 8"), std::string::npos);
}

TEST(SlamBinary, ABadGroundTruthIsNamedBeforeAnyWorkAndNoStaleReportStays) {
    lodestone::test::TempDir dir;
    const std::string out = dir.file("out");
    // A previous run's outputs in the folder...
    fs::create_directories(out);
    std::ofstream(dir.file("out/report.json")) << "{\"from\": \"an earlier run\"}\n";
    std::ofstream(dir.file("out/trajectory.png")) << "old";
    std::ofstream(dir.file("bad.tum")) << "1.0 0 0 0 0 0 0 1\n2.0 0 0 0 x 0 0 1\n";
    const auto r = lodestone::test::runCommand(kSlam + " --rawlog " + kOfficeRawlog +
                                               " --ground-truth " + dir.file("bad.tum") +
                                               " --config " + kConfigDir + "/slam/slam.ini --out " + out);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("bad.tum"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("line 2"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("done "), std::string::npos) << "refused before the run: " << r.output;
    // ... are left alone when the run never starts (nothing of it was written) ...
    EXPECT_TRUE(fs::exists(dir.file("out/report.json")));
    // ... and are gone once a run starts, so none stays beside this run's results.
    const auto ok = lodestone::test::runCommand(kSlam + " --rawlog " + kOfficeRawlog + " --config " +
                                                kConfigDir + "/slam/slam.ini --max-seconds 2 --quiet --out " + out);
    ASSERT_EQ(ok.exitCode, 0) << ok.output;
    EXPECT_FALSE(fs::exists(dir.file("out/trajectory.png"))) << "no ground truth: no plot of it";
    EXPECT_EQ(lodestone::test::readTextFile(dir.file("out/report.json")).find("an earlier run"), std::string::npos);
    EXPECT_FALSE(fs::exists(dir.file("out/report.json.partial")));
}

TEST(SlamBinary, MrptsStockActionsAndSensoryFramesRawlogBecomesMotion) {
    // MRPT's localization_demo.rawlog: odometry as CActionRobotMovement2D without timestamps
    // and with an encoder flag MRPT never set (byte 8). It ran to "0 nodes, 1.14e9 s of data",
    // exit 0; its actions are now the motion, stamped by the frames that follow them.
    const std::string stock = (lodestone::test::mrptDatasetsDir() / "localization_demo.rawlog").string();
    if (!fs::exists(stock)) GTEST_SKIP() << "MRPT's sample datasets are not installed";
    lodestone::test::TempDir dir;
    const auto r = lodestone::test::runCommand(kSlam + " --rawlog " + stock + " --config " +
                                               kConfigDir + "/slam/odometry_only.ini --quiet --out " +
                                               dir.file("out"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.output, m, std::regex("([0-9]+) nodes.* ([0-9.]+) s of data")))
        << r.output;
    EXPECT_GE(std::stoi(m[1]), 30) << r.output;        // 37 actions over ~6 m
    EXPECT_NEAR(std::stod(m[2]), 9.3, 0.5) << r.output;  // the frames' time span
}
