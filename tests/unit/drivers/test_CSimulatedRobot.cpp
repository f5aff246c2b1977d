// CSimulatedRobot: a scenario as a live MRPT sensor - in process, and inside stock
// rawlog-grabber through Lodestone's plugin.
#include <gtest/gtest.h>
#include <lodestone/drivers/CSimulatedRobot.h>
#include <lodestone/drivers/registerDrivers.h>
#include <lodestone/obs/registerAllClasses.h>
#include <lodestone/sim/Scenario.h>
#include <lodestone/sim/SimulatorSource.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>

#include "StockTools.h"
#include "TestPaths.h"

using lodestone::drivers::CSimulatedRobot;
namespace fs = std::filesystem;

namespace {
const std::string kOffice = std::string(LODESTONE_CONFIG_INI_DIR) + "/scenarios/office.ini";

mrpt::hwdrivers::CGenericSensor::Ptr configured(const std::string& ini) {
    lodestone::registerAllClasses();
    lodestone::drivers::registerDrivers();
    auto sensor = mrpt::hwdrivers::CGenericSensor::createSensorPtr("CSimulatedRobot");
    if (!sensor) throw std::runtime_error("CSimulatedRobot is not in MRPT's sensor factory");
    mrpt::config::CConfigFileMemory config(ini);
    sensor->loadConfig(config, "SIM");
    return sensor;
}

std::vector<mrpt::obs::CObservation::Ptr> runToTheEnd(mrpt::hwdrivers::CGenericSensor& s) {
    auto& robot = dynamic_cast<CSimulatedRobot&>(s);
    std::vector<mrpt::obs::CObservation::Ptr> out;
    while (!robot.finished()) {
        robot.doProcess();
        for (const auto& [t, o] : robot.getObservations()) {
            out.push_back(std::dynamic_pointer_cast<mrpt::obs::CObservation>(o));
        }
    }
    for (const auto& [t, o] : robot.getObservations()) {
        out.push_back(std::dynamic_pointer_cast<mrpt::obs::CObservation>(o));
    }
    return out;
}
}  // namespace

TEST(CSimulatedRobot, EmitsWhatTheSimulatorMakesOnTheGrabsClock) {
    auto sensor = configured("[SIM]\nscenario = " + kOffice +
                             "\ntime_scale = 1000\ncamera = 64x48@2\nmax_seconds = 3\n");
    sensor->initialize();
    const double before = mrpt::Clock::toDouble(mrpt::Clock::now());
    const auto got = runToTheEnd(*sensor);

    auto scenario = lodestone::sim::Scenario::load(kOffice);
    ASSERT_TRUE(scenario.camera.override("64x48@2"));
    lodestone::sim::SimulatorSource sim(scenario, 0);
    std::map<std::string, std::size_t> expected, seen;
    while (auto o = sim.next()) {
        if (mrpt::Clock::toDouble(o->timestamp) - sim.startTime() > 3) break;
        ++expected[o->sensorLabel];
    }
    for (const auto& o : got) ++seen[o->sensorLabel];
    EXPECT_EQ(seen, expected);
    ASSERT_GT(got.size(), 100u);
    // Moved onto the wall clock of the grab, the spacing of the scenario kept.
    const double t0 = mrpt::Clock::toDouble(got.front()->timestamp);
    const double t1 = mrpt::Clock::toDouble(got.back()->timestamp);
    EXPECT_NEAR(t0, before, 2.0);
    EXPECT_NEAR(t1 - t0, 3.0, 0.05);
    for (std::size_t i = 1; i < got.size(); ++i) {
        ASSERT_LE(got[i - 1]->timestamp, got[i]->timestamp) << "observation " << i;
    }
}

TEST(CSimulatedRobot, NeverRunsAheadOfTheClock) {
    auto sensor = configured("[SIM]\nscenario = " + kOffice +
                             "\ntime_scale = 2\ncamera = 32x24@1\nmax_seconds = 2\n");
    sensor->initialize();
    const auto start = std::chrono::steady_clock::now();
    const auto got = runToTheEnd(*sensor);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // Two scenario seconds at twice real time: the last observation is not due before 1 s.
    EXPECT_GE(wall, 0.98);
    EXPECT_FALSE(got.empty());
}

TEST(CSimulatedRobot, ConfigurationMistakesNameTheSectionAndKey) {
    const auto refusal = [](const std::string& ini) -> std::string {
        try {
            auto s = configured(ini);
            s->initialize();
        } catch (const std::exception& e) {
            return e.what();
        }
        return "(accepted)";
    };
    const std::string missing = refusal("[SIM]\ntime_scale = 2\n");
    EXPECT_NE(missing.find("section 'SIM', key 'scenario': missing"), std::string::npos) << missing;
    const std::string zero = refusal("[SIM]\nscenario = " + kOffice + "\ntime_scale = 0\n");
    EXPECT_NE(zero.find("key 'time_scale'"), std::string::npos) << zero;
    const std::string absent = refusal("[SIM]\nscenario = /nonexistent.ini\n");
    EXPECT_NE(absent.find("key 'scenario'"), std::string::npos) << absent;
    EXPECT_NE(absent.find("/nonexistent.ini"), std::string::npos) << absent;
    const std::string camera = refusal("[SIM]\nscenario = " + kOffice + "\ncamera = big\n");
    EXPECT_NE(camera.find("key 'camera'"), std::string::npos) << camera;
}

TEST(CSimulatedRobot, StockRawlogGrabberGrabsItThroughThePlugin) {
    if (lodestone::test::runCommand("command -v rawlog-grabber").exitCode != 0) {
        GTEST_SKIP() << "rawlog-grabber (mrpt-apps) not installed";
    }
    lodestone::test::TempDir dir;
    std::ofstream(dir.file("grab.ini"))
        << "[global]\nrawlog_prefix = " << dir.file("grab") << "\ntime_between_launches = 100\n"
        << "use_sensoryframes = 0\nGRABBER_PERIOD_MS = 20\n\n"
        << "[SIM]\ndriver = CSimulatedRobot\nprocess_rate = 50\nscenario = " << kOffice
        << "\ntime_scale = 8\ncamera = 64x48@2\nmax_seconds = 8\n";
    // Stock rawlog-grabber stops on a key press; it gets one after the scenario's second of
    // wall time (8 s at time_scale 8) and some slack.
    const auto r = lodestone::test::runCommand("(sleep 4; echo q) | timeout 60 " +
                                               lodestone::test::stockToolEnv() + "rawlog-grabber -p '" +
                                               std::string(LODESTONE_MRPT_PLUGIN) + "' '" +
                                               dir.file("grab.ini") + "'");
    ASSERT_EQ(r.exitCode, 0) << r.output.substr(0, 3000);
    std::string rawlog;
    for (const auto& e : fs::directory_iterator(dir.path())) {
        if (e.path().extension() == ".rawlog") rawlog = e.path().string();
    }
    ASSERT_FALSE(rawlog.empty()) << r.output.substr(0, 3000);
    auto info = lodestone::test::rawlogEditInfo(rawlog, LODESTONE_MRPT_PLUGIN);
    // 8 s of the office scenario: magnetometers at 100 Hz, wheels at 50 Hz, camera at 2 Hz
    // (stock rawlog-grabber's final flush is known to drop part of its queue: MRPT_NOTES.md).
    EXPECT_GE(info.occurrences["MAG_LEFT"], 780);
    EXPECT_LE(info.occurrences["MAG_LEFT"], 801);
    EXPECT_GE(info.occurrences["WHEELS"], 390);
    EXPECT_GE(info.occurrences["RGBD"], 15);
}
