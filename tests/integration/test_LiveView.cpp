// lodestone-slam --view: MRPT's window with the run as it goes, on an Xvfb display; the run's
// outputs are the same with the view as without; without a display the run goes on.
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <filesystem>

#include "StockTools.h"
#include "TestPaths.h"
#include "XwdImage.h"

namespace {
const std::string kSlam = LODESTONE_SLAM_BINARY;
const std::string kConfigDir = LODESTONE_CONFIG_INI_DIR;
const std::string kOfficeRawlog = LODESTONE_OFFICE_RAWLOG;

bool have(const std::string& program) {
    return lodestone::test::runCommand("command -v " + program).exitCode == 0;
}

std::string slamOn(const std::string& out, const std::string& extra) {
    return kSlam + " --rawlog " + kOfficeRawlog + " --config " + kConfigDir + "/slam/slam.ini --out " + out +
           " --quiet --max-seconds 25 " + extra;
}
}  // namespace

TEST(LiveView, TheWindowShowsTheRunAsItGoesUnderXvfb) {
    for (const char* p : {"xvfb-run", "xwd", "xwininfo", "xdotool"}) {
        if (!have(p)) GTEST_SKIP() << p << " not installed (scripts/install-deps.sh installs xvfb, x11-apps, "
                                   << "x11-utils, xdotool); no X server to open the view on";
    }
    namespace fs = std::filesystem;
    lodestone::test::TempDir dir;
    const fs::path shots = LODESTONE_SCREENSHOT_DIR;
    fs::create_directories(shots);
    const std::string xwd = (shots / "live_view.xwd").string();
    fs::remove(xwd);
    // (the simulator in memory runs at a few times real time: long enough to be caught running)
    const auto r = lodestone::test::runCommand(
        std::string(LODESTONE_X_SCREENSHOT) + " '" + xwd + "' Lodestone 4 " + kSlam + " --sim " + kConfigDir +
        "/scenarios/office.ini --config " + kConfigDir + "/slam/slam.ini --out " + dir.path().string() +
        " --quiet --max-seconds 60 --view");
    ASSERT_EQ(r.exitCode, 0) << "3: no window, 4: lodestone-slam exited first, 5: no screenshot\n" << r.output;
    const cv::Mat3b screen = lodestone::test::readXwd(xwd);
    cv::imwrite((shots / "live_view.png").string(), screen, {cv::IMWRITE_PNG_COMPRESSION, 9});
    // The overlay's white text at the top left, the grid, the path's colours.
    int white = 0;
    for (int y = 0; y < 60; ++y)
        for (int x = 0; x < 300; ++x) white += screen(y, x) == cv::Vec3b(255, 255, 255);
    EXPECT_GT(white, 100) << "no status text at the top left";
    EXPECT_GT(lodestone::test::distinctColours(screen), 10u);
}

TEST(LiveView, TheRunsOutputsAreTheSameWithTheViewAsWithout) {
    if (!have("xvfb-run")) GTEST_SKIP() << "xvfb-run not installed: no X server to open the view on";
    lodestone::test::TempDir with, without;
    const auto a = lodestone::test::runCommand("xvfb-run -a " + slamOn(with.path().string(), "--view"));
    ASSERT_EQ(a.exitCode, 0) << a.output;
    const auto b = lodestone::test::runCommand(slamOn(without.path().string(), ""));
    ASSERT_EQ(b.exitCode, 0) << b.output;
    for (const char* file : {"trajectory.tum", "graph.graph", "closures.csv"}) {
        const std::string x = lodestone::test::readTextFile(with.file(file));
        EXPECT_FALSE(x.empty()) << file;
        EXPECT_EQ(x, lodestone::test::readTextFile(without.file(file))) << file;
    }
}

TEST(LiveView, WithoutADisplayTheRunGoesOnAndSaysSo) {
    lodestone::test::TempDir dir;
    const auto r = lodestone::test::runCommand("env -u DISPLAY " + slamOn(dir.path().string(), "--view"));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("--view: no display"), std::string::npos) << r.output;
    EXPECT_FALSE(lodestone::test::readTextFile(dir.file("trajectory.tum")).empty());
}
