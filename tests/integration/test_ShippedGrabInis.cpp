// The grab INIs config_ini/grab/ ships, run as a user runs them from the repository's root.
#include <gtest/gtest.h>
#include <lodestone/inspect/RawlogSummary.h>
#include <lodestone/obs/registerAllClasses.h>

#include <filesystem>

#include "StockTools.h"
#include "TestPaths.h"

namespace fs = std::filesystem;
using lodestone::test::runCommand;

namespace {
const std::string kGrab = LODESTONE_GRAB_BINARY;

/** A scratch folder standing in for the repository's root: config_ini/ linked in, so the
 * INIs' relative paths resolve and their outputs land in the scratch folder. */
std::string rootLike(const lodestone::test::TempDir& dir) {
    fs::create_directory_symlink(LODESTONE_CONFIG_INI_DIR, dir.file("config_ini"));
    return dir.path().string();
}
}  // namespace

TEST(ShippedGrabInis, TheSimulatedRobotGrabsAsShipped) {
    lodestone::test::TempDir dir;
    const std::string root = rootLike(dir);
    const auto r = runCommand("cd " + root + " && timeout 60 " + kGrab +
                              " config_ini/grab/sim_robot.ini --duration 3 -q");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ASSERT_TRUE(fs::exists(root + "/out/live.rawlog.gz")) << r.output;
    EXPECT_TRUE(fs::exists(root + "/out/live.gt.tum")) << r.output;
    lodestone::registerAllClasses();
    const auto summary = lodestone::inspect::summarizeRawlog(root + "/out/live.rawlog.gz");
    EXPECT_FALSE(summary.error.has_value());
    EXPECT_GT(summary.entries, 100u);  // 3 s of wheels, two magnetometers and a camera
}

TEST(ShippedGrabInis, ThePapersRobotWithoutItsHardwareNamesTheSensorThatCannotStart) {
    for (const char* port : {"/dev/ttyUSB0", "/dev/ttyUSB1", "/dev/ttyUSB2"}) {
        if (fs::exists(port)) GTEST_SKIP() << port << " exists here: a sensor may be plugged in";
    }
    lodestone::test::TempDir dir;
    const std::string root = rootLike(dir);
    const auto r = runCommand("cd " + root + " && timeout 60 " + kGrab +
                              " config_ini/grab/kobuki_xsens_openni2.ini --duration 1 -q");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    // The INI itself is read without complaint (no key or driver named as wrong): the first
    // sensor to start (sections in name order: MAG_LEFT) fails on its missing port, named.
    EXPECT_NE(r.output.find("sensor section 'MAG_LEFT'"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("/dev/ttyUSB1"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(root + "/out/kobuki.rawlog.gz"));
}
