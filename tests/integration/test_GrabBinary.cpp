// lodestone-grab as a user runs it: the simulated robot grabbed and run through lodestone-slam;
// SIGINT and SIGKILL mid-grab; a sensor that cannot start, one that dies while grabbing.
#include <gtest/gtest.h>
#include <lodestone/eval/TrajectoryError.h>
#include <lodestone/inspect/RawlogSummary.h>
#include <lodestone/io/RawlogReader.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/obs/registerAllClasses.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>

#include "StockTools.h"
#include "TestPaths.h"

namespace fs = std::filesystem;
using lodestone::test::runCommand;

namespace {
const std::string kGrab = LODESTONE_GRAB_BINARY;
const std::string kSlam = LODESTONE_SLAM_BINARY;
const std::string kOffice = std::string(LODESTONE_CONFIG_INI_DIR) + "/scenarios/office.ini";

// A grab INI of the simulated office robot; `extra` lines go into its section.
std::string writeGrabIni(const lodestone::test::TempDir& dir, const std::string& extra,
                         const std::string& more = "") {
    const std::string path = dir.file("grab.ini");
    std::ofstream(path) << "[global]\nrawlog_prefix = " << dir.file("run") << "\n\n"
                        << "[SIM]\ndriver = CSimulatedRobot\nprocess_rate = 100\nscenario = "
                        << kOffice << "\ncamera = 160x120@5\nground_truth = " << dir.file("run.gt.tum")
                        << "\n" << extra << "\n" << more;
    return path;
}

// Starts the grabber in the background and signals it 3 s after it began writing: its start-up
// (the scenario loaded, the sensors started) takes 0.7 s on an idle machine and several seconds
// on a loaded one, which a fixed sleep would count as grabbing time.
std::string grabThenSignal(const std::string& ini, const std::string& rawlogPartial,
                           const char* signal) {
    return kGrab + " " + ini + " -q & pid=$!; for i in $(seq 300); do [ -s " + rawlogPartial +
           " ] && break; sleep 0.1; done; sleep 3; kill -" + signal + " $pid; wait $pid";
}

long numberIn(const std::string& text, const std::string& pattern) {
    std::smatch m;
    return std::regex_search(text, m, std::regex(pattern)) ? std::stol(m[1]) : -1;
}

struct ReadBack {
    std::size_t entries{0};
    double lastTime{0};
    bool error{false};
};
ReadBack readBack(const std::string& path) {
    lodestone::registerAllClasses();
    ReadBack r;
    const auto s = lodestone::inspect::summarizeRawlog(path);
    r.entries = s.entries;
    r.error = s.error.has_value();
    if (s.last) r.lastTime = mrpt::Clock::toDouble(*s.last);
    return r;
}
}  // namespace

TEST(GrabBinary, TheSimulatedRobotGrabbedAtTimeScale4RunsThroughSlam) {
    lodestone::test::TempDir dir;
    const auto ini = writeGrabIni(dir, "time_scale = 4\nmax_seconds = 10");
    const auto r = runCommand("timeout 120 " + kGrab + " " + ini + " -q");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("stopped by sensors finished"), std::string::npos) << r.output;
    const long written = numberIn(r.output, "lodestone-grab: ([0-9]+) observations");
    const auto back = readBack(dir.file("run.rawlog.gz"));
    EXPECT_FALSE(back.error);
    EXPECT_EQ(static_cast<long>(back.entries), written);
    ASSERT_TRUE(fs::exists(dir.file("run_Images")));
    if (lodestone::test::haveRawlogEdit()) {  // stock MRPT reads it through our plugin
        auto info = lodestone::test::rawlogEditInfo(dir.file("run.rawlog.gz"), LODESTONE_MRPT_PLUGIN);
        EXPECT_EQ(info.objects, written);
        EXPECT_GE(info.occurrences["MAG_LEFT"], 990);
    }
    const auto s = runCommand(kSlam + " --rawlog " + dir.file("run.rawlog.gz") + " --ground-truth " +
                              dir.file("run.gt.tum") + " --config " + LODESTONE_CONFIG_INI_DIR +
                              "/slam/slam.ini --quiet --out " + dir.file("slam"));
    ASSERT_EQ(s.exitCode, 0) << s.output;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(s.output, m, std::regex("ATE RMSE ([0-9.]+) m"))) << s.output;
    EXPECT_LT(std::stod(m[1]), 0.02) << s.output;  // measured 0.0056 m
}

TEST(GrabBinary, SigintWritesEveryObservationProducedAndExitsZero) {
    lodestone::test::TempDir dir;
    const auto ini = writeGrabIni(dir, "time_scale = 1");
    const auto r = runCommand(grabThenSignal(ini, dir.file("run.rawlog.gz.partial"), "INT"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("stopped by signal"), std::string::npos) << r.output;
    const long produced = numberIn(r.output, "SIM \\(CSimulatedRobot\\): ([0-9]+) observations");
    ASSERT_GT(produced, 500) << r.output;  // ~3 s of 100 + 100 + 50 + 5 Hz
    const auto back = readBack(dir.file("run.rawlog.gz"));
    EXPECT_FALSE(back.error);
    EXPECT_EQ(static_cast<long>(back.entries), produced);
    EXPECT_FALSE(fs::exists(dir.file("run.rawlog.gz.partial")));
}

TEST(GrabBinary, SigkillLeavesAReadableRawlogMissingAtMostOneSecond) {
    lodestone::test::TempDir dir;
    const auto ini = writeGrabIni(dir, "time_scale = 1");
    runCommand(grabThenSignal(ini, dir.file("run.rawlog.gz.partial"), "KILL"));
    // Killed: no rename, the .partial files hold what was flushed.
    const std::string rawlog = dir.file("run.rawlog.gz.partial");
    ASSERT_TRUE(fs::exists(rawlog));
    const auto back = readBack(rawlog);
    EXPECT_GT(back.entries, 300u);
    // The truth file is written line by line as observations are emitted: its last line is
    // the newest observation the sensor produced.
    const auto truth = lodestone::io::readTumTrajectory(dir.file("run.gt.tum.partial"));
    ASSERT_FALSE(truth.empty());
    EXPECT_LE(truth.back().timestamp - back.lastTime, 1.0)
        << "lost " << truth.back().timestamp - back.lastTime << " s";
}

TEST(GrabBinary, AnUnknownDriverIsRefusedNamingItsSection) {
    lodestone::test::TempDir dir;
    const auto ini = writeGrabIni(dir, "", "[LASER]\ndriver = CNoSuchLaser\n");
    const auto r = runCommand(kGrab + " " + ini + " -q");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("sensor section 'LASER': unknown driver 'CNoSuchLaser'"), std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(dir.file("run.rawlog.gz")));
    EXPECT_FALSE(fs::exists(dir.file("run.rawlog.gz.partial")));
}

TEST(GrabBinary, ASensorThatDiesIsReportedAndTheOthersGoOn) {
    lodestone::test::TempDir dir;
    const auto ini = writeGrabIni(dir, "time_scale = 4\nmax_seconds = 8",
                                  "[FLAKY]\ndriver = CFailingSensor\nprocess_rate = 20\nfail_after = 10\n");
    const auto r = runCommand("timeout 60 " + kGrab + " " + ini + " -q --plugin " +
                              LODESTONE_FAILING_SENSOR_PLUGIN);
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("sensor section 'FLAKY' died while grabbing"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("the test sensor's cable came out"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("SIM (CSimulatedRobot): "), std::string::npos);
    EXPECT_NE(r.output.find(", finished"), std::string::npos) << r.output;  // SIM ran to its end
    const long flaky = numberIn(r.output, "FLAKY \\(CFailingSensor\\): ([0-9]+) observations");
    EXPECT_EQ(flaky, 9);
    const auto back = readBack(dir.file("run.rawlog.gz"));
    EXPECT_FALSE(back.error);
    EXPECT_GT(back.entries, 1500u);
}

TEST(GrabBinary, ConfigurationMistakes) {
    lodestone::test::TempDir dir;
    std::ofstream(dir.file("typo.ini")) << "[global]\nreorder_windw = 0.5\n[SIM]\ndriver = CSimulatedRobot\n";
    auto r = runCommand(kGrab + " " + dir.file("typo.ini") + " -q");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("reorder_windw"), std::string::npos) << r.output;
    std::ofstream(dir.file("empty.ini")) << "[global]\n";
    r = runCommand(kGrab + " " + dir.file("empty.ini") + " -q");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("no sensor section"), std::string::npos) << r.output;
    r = runCommand(kGrab + " " + dir.file("nonexistent.ini"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    r = runCommand(kGrab + " " + writeGrabIni(dir, "") + " --duration -1");
    EXPECT_EQ(r.exitCode, 2) << r.output;
}

TEST(GrabBinary, AnXsensImuOnAMissingPortIsGivenUpOnInBoundedTime) {
    // MRPT's CIMUXSens_MT4 hangs over a minute on a port that does not exist (MRPT_NOTES.md);
    // wrapped in CMagnetometerFromImu its start is bounded by init_timeout_s.
    lodestone::test::TempDir dir;
    std::ofstream(dir.file("xsens.ini"))
        << "[global]\nrawlog_prefix = " << dir.file("run") << "\n\n[MAG]\ndriver = CMagnetometerFromImu\n"
        << "imu_driver = CIMUXSens_MT4\nimu_section = XSENS\nunit = normalized:50\ninit_timeout_s = 1\n\n"
        << "[XSENS]\nportname_LIN = /dev/ttyUSB-lodestone-missing\n";
    const auto start = std::chrono::steady_clock::now();
    const auto r = runCommand("timeout 60 " + kGrab + " " + dir.file("xsens.ini") + " -q");
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("did not start within 1 s on port /dev/ttyUSB-lodestone-missing"),
              std::string::npos)
        << r.output;
    EXPECT_LT(wall, 10.0);
    EXPECT_FALSE(fs::exists(dir.file("run.rawlog.gz.partial")));
}

TEST(GrabBinary, AnOpenNI2CameraThatIsNotThereIsAnErrorNotAnAbort) {
    // Stock COpenNI2Sensor without a camera: doProcess() asserts and the destructor throws -
    // the process would end with SIGABRT. lodestone-grab runs it through its guard.
    lodestone::test::TempDir dir;
    std::ofstream(dir.file("oni.ini")) << "[global]\nrawlog_prefix = " << dir.file("run")
                                       << "\n\n[CAM]\ndriver = COpenNI2Sensor\nsensorLabel = RGBD\n";
    const auto r = runCommand("timeout 60 " + kGrab + " " + dir.file("oni.ini") + " -q");
    if (r.exitCode == 0) GTEST_SKIP() << "an OpenNI2 camera is attached to this machine";
    EXPECT_EQ(r.exitCode, 1) << r.output;  // not 134 (abort)
    EXPECT_NE(r.output.find("sensor section 'CAM': no OpenNI2 device found"), std::string::npos)
        << r.output;
}

TEST(GrabBinary, LiveSlamMatchesTheOfflineRunOnTheGrabbedRawlog) {
    lodestone::test::TempDir dir;
    const auto ini = writeGrabIni(dir, "time_scale = 4\nmax_seconds = 12");
    const auto r = runCommand("timeout 120 " + kGrab + " " + ini + " -q --slam " +
                              LODESTONE_CONFIG_INI_DIR + "/slam/slam.ini");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const long nodes = numberIn(r.output, "live SLAM: ([0-9]+) nodes");
    EXPECT_GT(nodes, 10) << r.output;
    ASSERT_NE(r.output.find("RGB-D frames skipped"), std::string::npos) << r.output;
    for (const char* f : {"trajectory.tum", "graph.graph", "report.json", "nodes.csv", "field_map.png"}) {
        EXPECT_TRUE(fs::exists(dir.file(std::string("run_slam/") + f))) << f;
    }
    const auto truth = lodestone::io::readTumTrajectory(dir.file("run.gt.tum"));
    const auto live = lodestone::io::readTumTrajectory(dir.file("run_slam/trajectory.tum"));
    const auto s = runCommand(kSlam + " --rawlog " + dir.file("run.rawlog.gz") + " --config " +
                              LODESTONE_CONFIG_INI_DIR + "/slam/slam.ini --quiet --out " + dir.file("offline"));
    ASSERT_EQ(s.exitCode, 0) << s.output;
    const auto offline = lodestone::io::readTumTrajectory(dir.file("offline/trajectory.tum"));
    const double liveAte = lodestone::eval::absoluteTrajectoryError(live, truth).rmse;
    const double offlineAte = lodestone::eval::absoluteTrajectoryError(offline, truth).rmse;
    EXPECT_LT(liveAte, 0.02);
    EXPECT_NEAR(liveAte, offlineAte, 0.01) << "live " << liveAte << " m, offline " << offlineAte << " m";
}

TEST(GrabBinary, LiveSlamWithTheViewUnderXvfb) {
    if (runCommand("command -v xvfb-run").exitCode != 0)
        GTEST_SKIP() << "xvfb-run not installed: no X server to open the view on";
    lodestone::test::TempDir dir;
    const auto ini = writeGrabIni(dir, "time_scale = 4\nmax_seconds = 12");
    const auto r = runCommand("xvfb-run -a timeout 120 " + kGrab + " " + ini + " -q --view --slam " +
                              LODESTONE_CONFIG_INI_DIR + "/slam/slam.ini");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("no display"), std::string::npos) << r.output;
    EXPECT_GT(numberIn(r.output, "live SLAM: ([0-9]+) nodes"), 10) << r.output;
    EXPECT_TRUE(fs::exists(dir.file("run_slam/trajectory.tum")));
    // Without --slam there is nothing to view.
    EXPECT_EQ(runCommand(kGrab + " " + ini + " -q --view").exitCode, 2);
}

TEST(GrabBinary, LiveSlamFusesItsDenseModelAsItGoes) {
    // A live run cannot read its frames again after it: --mesh fuses keyframes as they are made.
    lodestone::test::TempDir dir;
    const auto ini = writeGrabIni(dir, "time_scale = 4\nmax_seconds = 12");
    const auto r = runCommand("timeout 120 " + kGrab + " " + ini + " -q --mesh --slam " +
                              LODESTONE_CONFIG_INI_DIR + "/slam/slam.ini");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ASSERT_TRUE(fs::exists(dir.file("run_slam/mesh.ply"))) << r.output;
    const std::string report = lodestone::test::readTextFile(dir.file("run_slam/report.json"));
    EXPECT_NE(report.find("\"fusion\": \"while_running\""), std::string::npos) << report;
    EXPECT_GT(numberIn(report, "\"frames_fused\": ([0-9]+)"), 5) << report;
    EXPECT_FALSE(fs::exists(dir.file("run_slam/mesh.ply.frames")));
    // Without --slam there is nothing to fuse.
    EXPECT_EQ(runCommand(kGrab + " " + ini + " -q --mesh").exitCode, 2);
}

TEST(GrabBinary, ABadSlamIniIsRefusedBeforeGrabbing) {
    lodestone::test::TempDir dir;
    std::ofstream(dir.file("slam.ini")) << "[graphslam]\nnode_decider = FusedOdometryNDR\n";
    const auto r = runCommand(kGrab + " " + writeGrabIni(dir, "time_scale = 4") + " -q --slam " +
                              dir.file("slam.ini"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("FusedOdometryNDR"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.file("run.rawlog.gz")));
    EXPECT_FALSE(fs::exists(dir.file("run.rawlog.gz.partial")));
}

TEST(GrabBinary, AMapMadeByOtherDecidersIsRefusedBeforeGrabbing) {
    // A map of the office saved with the GP magnetic closer; live SLAM with the window closer.
    lodestone::test::TempDir dir;
    const std::string ini = std::string(LODESTONE_CONFIG_INI_DIR) + "/slam/";
    ASSERT_EQ(runCommand(kSlam + " --sim " + kOffice + " --config " + ini +
                         "magnetic_only.ini --max-seconds 5 -q --out " + dir.file("office") +
                         " --map-out " + dir.file("map"))
                  .exitCode,
              0);
    const auto r = runCommand(kGrab + " " + writeGrabIni(dir, "time_scale = 4") + " -q --slam " +
                              ini + "magnetic_window.ini --map-in " + dir.file("map"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("MagneticGpERD"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.file("run.rawlog.gz")));
    // --map-in is live SLAM's.
    EXPECT_EQ(runCommand(kGrab + " " + writeGrabIni(dir, "time_scale = 4") + " -q --map-in " +
                         dir.file("map"))
                  .exitCode,
              2);
}

TEST(GrabBinary, SigintDuringLiveSlamEndsBothCleanly) {
    lodestone::test::TempDir dir;
    const auto ini = writeGrabIni(dir, "time_scale = 1");
    const auto r = runCommand(kGrab + " " + ini + " -q --slam " + LODESTONE_CONFIG_INI_DIR +
                              "/slam/slam.ini & pid=$!; sleep 4; kill -INT $pid; wait $pid");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("stopped by signal"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(dir.file("run.rawlog.gz")));
    EXPECT_TRUE(fs::exists(dir.file("run_slam/report.json")));  // written last: the run completed
    EXPECT_GT(numberIn(r.output, "live SLAM: ([0-9]+) nodes"), 3) << r.output;
}
