// Lodestone's MRPT plugin inside stock MRPT tools: rawlog-edit and RawLogViewer read our
// rawlogs once the plugin is loaded.
#include <gtest/gtest.h>
#include <lodestone/inspect/RawlogSummary.h>
#include <lodestone/obs/registerAllClasses.h>
#include <opencv2/imgcodecs.hpp>

#include <filesystem>

#include "StockTools.h"
#include "TestPaths.h"
#include "XwdImage.h"

namespace {
const std::string kPlugin = LODESTONE_MRPT_PLUGIN;
const std::string kOffice = LODESTONE_OFFICE_RAWLOG;

bool have(const std::string& program) {
    return lodestone::test::runCommand("command -v " + program).exitCode == 0;
}
}  // namespace

TEST(MrptPlugin, RawlogEditCountsTheMagnetometerEntriesOfTheBundledSample) {
    if (!lodestone::test::haveRawlogEdit()) GTEST_SKIP() << "rawlog-edit (mrpt-apps) not installed";
    lodestone::registerAllClasses();
    const auto ours = lodestone::inspect::summarizeRawlog(kOffice);
    ASSERT_FALSE(ours.error) << *ours.error;
    const auto stock = lodestone::test::rawlogEditInfo(kOffice, kPlugin);
    EXPECT_EQ(stock.objects, static_cast<long>(ours.entries));
    for (const std::string label : {"MAG_LEFT", "MAG_RIGHT"}) {
        ASSERT_TRUE(ours.sensors.count(label)) << label;
        ASSERT_TRUE(stock.occurrences.count(label)) << label << " not in rawlog-edit --info";
        EXPECT_GT(stock.occurrences.at(label), 1000) << label;
        EXPECT_EQ(stock.occurrences.at(label), static_cast<long>(ours.sensors.at(label).count))
            << label;
    }
}

TEST(MrptPlugin, WithoutThePluginRawlogEditCannotReadOurClasses) {
    // The reason the plugin exists: if this starts to pass, MRPT learnt to skip unknown classes.
    if (!lodestone::test::haveRawlogEdit()) GTEST_SKIP() << "rawlog-edit (mrpt-apps) not installed";
    const auto stock = lodestone::test::rawlogEditInfo(kOffice);
    EXPECT_EQ(stock.occurrences.count("MAG_LEFT"), 0u);
}

TEST(MrptPlugin, RawLogViewerOpensTheBundledSampleUnderXvfb) {
    for (const char* p : {"RawLogViewer", "xvfb-run", "xwd", "xwininfo", "xdotool"}) {
        if (!have(p)) {
            GTEST_SKIP() << p << " not installed (scripts/install-deps.sh installs mrpt-apps, xvfb, "
                         << "x11-apps, x11-utils, xdotool); no X server to run RawLogViewer on";
        }
    }
    namespace fs = std::filesystem;
    const fs::path shots = LODESTONE_SCREENSHOT_DIR;
    fs::create_directories(shots);
    const std::string xwd = (shots / "rawlogviewer.xwd").string();
    fs::remove(xwd);
    // Entry 1 of the sample is a magnetometer reading: clicking it shows our class's
    // getDescriptionAsText() in RawLogViewer's text panel (the README's screenshot).
    const auto r = lodestone::test::runCommand(
        std::string(LODESTONE_X_SCREENSHOT) + " --dismiss 'Tip of the Day' --click 120,140 '" + xwd +
        "' 'RawlogViewer - Part of the MRPT project' 3 " + lodestone::test::stockToolEnv() +
        "RawLogViewer -l '" + kPlugin + "' '" +
        kOffice + "'");
    ASSERT_EQ(r.exitCode, 0) << "3: no window, 4: RawLogViewer exited, 5: no screenshot\n"
                             << r.output;
    const cv::Mat3b screen = lodestone::test::readXwd(xwd);
    cv::imwrite((shots / "rawlogviewer.png").string(), screen, {cv::IMWRITE_PNG_COMPRESSION, 9});
    // A blank Xvfb screen is one colour; RawLogViewer's tree, text and plots give hundreds.
    EXPECT_GT(lodestone::test::distinctColours(screen), 50u);
}
