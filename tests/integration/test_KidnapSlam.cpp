// Kidnap recovery end to end, as a user runs it: lodestone-slam on a short simulated kidnap
// (one lap mapped, lifted early in lap 2, put down on the mapped south leg), then
// `lodestone-eval relocation` against the simulator's truth: relocated, not wrong, close.
// Once with the wheel-drop sensor, once with the second detector alone (VO and magnetometers
// against the encoders).
#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include "StockTools.h"
#include "TestPaths.h"

namespace {
const std::string kSlam = LODESTONE_SLAM_BINARY;
const std::string kEval = LODESTONE_EVAL_BINARY;
const std::string kConfigDir = LODESTONE_CONFIG_INI_DIR;
const std::string kScenario = LODESTONE_TEST_DATA_DIR "/kidnap_short.ini";

/** slam.ini with the kidnap switches set. */
std::string configWith(const lodestone::test::TempDir& dir, bool wheelDrop, bool detector) {
    std::string ini = lodestone::test::readTextFile(kConfigDir + "/slam/slam.ini");
    const auto set = [&](const std::string& key, bool on) {
        const std::regex re("(\n" + key + "\\s*=\\s*)(true|false)");
        EXPECT_TRUE(std::regex_search(ini, re)) << key << " not in slam.ini";
        ini = std::regex_replace(ini, re, std::string("$1") + (on ? "true" : "false"));
    };
    set("kidnap_wheel_drop", wheelDrop);
    set("motion", detector);
    set("magnetic", detector);
    const std::string path = dir.file("slam_test.ini");
    std::ofstream(path) << ini;
    return path;
}

void expectRelocated(bool wheelDrop, bool detector) {
    lodestone::test::TempDir dir;
    const std::string out = dir.file("run");
    const auto run = lodestone::test::runCommand(kSlam + " --sim " + kScenario + " --config " +
                                                 configWith(dir, wheelDrop, detector) +
                                                 " --max-seconds 185 --quiet --out " + out);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const auto eval = lodestone::test::runCommand(kEval + " relocation " + out);
    ASSERT_EQ(eval.exitCode, 0) << eval.output;
    EXPECT_NE(eval.output.find("relocated 1 of 1, wrong 0, false detections 0"), std::string::npos)
        << eval.output;
    // | 1 | yes | yes | seconds | metres | position error | yaw error | wrong | deciders |
    std::smatch m;
    ASSERT_TRUE(std::regex_search(eval.output, m,
                                  std::regex(R"(\| 1 \| yes \| yes \| ([0-9.]+) \| ([0-9.]+) \| ([0-9.]+) \| ([0-9.]+) \|)")))
        << eval.output;
    EXPECT_LT(std::stod(m[2]), 4.0) << eval.output;   // metres travelled to the relocation
    EXPECT_LT(std::stod(m[3]), 0.25) << eval.output;  // position error there
    EXPECT_LT(std::stod(m[4]), 3.0) << eval.output;   // yaw error [deg]
    // The map before the lift kept its shape.
    ASSERT_TRUE(std::regex_search(eval.output, m, std::regex(R"(change ([-+][0-9.]+) m)"))) << eval.output;
    EXPECT_LT(std::abs(std::stod(m[1])), 0.01) << eval.output;
}
}  // namespace

TEST(KidnapSlam, RelocatedAfterAWheelDrop) { expectRelocated(true, false); }

TEST(KidnapSlam, RelocatedWithoutTheWheelDropSensor) { expectRelocated(false, true); }
