// lodestone-sim as a user runs it: every shipped scenario runs to its end (with a tiny camera,
// to keep the suite fast) and lodestone-inspect reads the rawlog it wrote.
#include <gtest/gtest.h>

#include <fstream>

#include "StockTools.h"
#include "TestPaths.h"

namespace {
const std::string kSim = LODESTONE_SIM_BINARY;
const std::string kInspect = LODESTONE_INSPECT_BINARY;
const std::string kConfigDir = LODESTONE_CONFIG_INI_DIR;

std::size_t countLines(const std::string& path, const std::string& prefix) {
    std::ifstream in(path);
    std::size_t n = 0;
    for (std::string l; std::getline(in, l);) n += l.rfind(prefix, 0) == 0;
    return n;
}
}  // namespace

class SimBinary : public ::testing::TestWithParam<std::string> {};

TEST_P(SimBinary, ScenarioRunsAndInspectReadsItsRawlog) {
    lodestone::test::TempDir dir;
    const auto out = dir.file(GetParam() + ".rawlog.gz");
    const auto sim = lodestone::test::runCommand(kSim + " --config " + kConfigDir + "/scenarios/" +
                                                 GetParam() + ".ini --camera 32x24@1 --out " + out);
    ASSERT_EQ(sim.exitCode, 0) << sim.output;
    const auto summary = lodestone::test::runCommand(kInspect + " summary " + out);
    ASSERT_EQ(summary.exitCode, 0) << summary.output;
    for (const char* label : {"MAG_LEFT", "MAG_RIGHT", "WHEELS", "RGBD"}) {
        EXPECT_NE(summary.output.find(label), std::string::npos) << label << "\n" << summary.output;
    }
    const std::size_t kidnaps = countLines(dir.file(GetParam() + ".events.txt"), "kidnap ");
    EXPECT_EQ(kidnaps, GetParam() == "paper_kidnap" ? 5u : 0u);
    EXPECT_EQ(summary.output.find("WHEEL_DROP") != std::string::npos, kidnaps > 0);
    // Ground truth: a pose for every observation.
    EXPECT_GT(countLines(dir.file(GetParam() + ".gt.tum"), "17"), 1000u);

    // Rewritten for stock MRPT, rawlog-edit reads all of it.
    if (!lodestone::test::haveRawlogEdit()) return;
    const auto stock = dir.file(GetParam() + "_stock.rawlog.gz");
    ASSERT_EQ(lodestone::test::runCommand(kInspect + " to-imu " + out + " " + stock).exitCode, 0);
    auto info = lodestone::test::rawlogEditInfo(stock);
    EXPECT_GT(info.objects, 1000);
    EXPECT_GT(info.occurrences["RGBD"], 10);
    // Wheel drops become comments (CObservationComment does not store a label).
    EXPECT_EQ(static_cast<std::size_t>(info.occurrences[""]), 2 * kidnaps);
}

INSTANTIATE_TEST_SUITE_P(Scenarios, SimBinary,
                         ::testing::Values("office", "corridor", "paper_loop", "paper_loop_qvga",
                                           "paper_kidnap"));

TEST(SimBinaryErrors, BadScenarioNamesTheKeyAndExits1) {
    lodestone::test::TempDir dir;
    const auto ini = dir.file("bad.ini");
    std::ifstream in(kConfigDir + "/scenarios/office.ini");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.find("laps      = 1"), 13, "lapz      = 1");
    std::ofstream(ini) << text;
    const auto r =
        lodestone::test::runCommand(kSim + " --config " + ini + " --out " + dir.file("x.rawlog"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("[path] key 'lapz'"), std::string::npos) << r.output;
    EXPECT_EQ(lodestone::test::runCommand(kSim + " --config " + ini + " --camera 12").exitCode, 2);
}

// A gyro recorded beside a hand-held camera: stock MRPT's CObservationIMU, read by our tools
// and by stock rawlog-edit as it is.
TEST(SimBinaryGyro, AHandHeldGyroIsRecordedAsStockImu) {
    lodestone::test::TempDir dir;
    const auto out = dir.file("hand.rawlog");
    const auto sim = lodestone::test::runCommand(kSim + " --config " + kConfigDir +
                                                 "/scenarios/office.ini --camera 32x24@5 --handheld --gyro --out " +
                                                 out);
    ASSERT_EQ(sim.exitCode, 0) << sim.output;
    const auto summary = lodestone::test::runCommand(kInspect + " summary " + out);
    ASSERT_EQ(summary.exitCode, 0) << summary.output;
    EXPECT_NE(summary.output.find("mrpt::obs::CObservationIMU"), std::string::npos) << summary.output;
    EXPECT_NE(summary.output.find("100.000"), std::string::npos) << summary.output;
    if (!lodestone::test::haveRawlogEdit()) GTEST_SKIP() << "rawlog-edit (mrpt-apps) not installed";
    auto info = lodestone::test::rawlogEditInfo(out);
    EXPECT_GT(info.occurrences["IMU"], 2000);
    EXPECT_GT(info.occurrences["RGBD"], 100);
}
