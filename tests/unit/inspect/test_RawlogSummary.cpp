#include <gtest/gtest.h>
#include <lodestone/inspect/RawlogSummary.h>
#include <lodestone/obs/registerAllClasses.h>

#include "RawlogTestHelpers.h"
#include "SampleObservations.h"
#include "StockTools.h"
#include "TestPaths.h"

using namespace lodestone;

class SummaryVsRawlogEdit : public ::testing::TestWithParam<std::string> {};

// Our per-sensor counts agree with rawlog-edit --info on stock datasets of both formats.
// rawlog-edit reads actions/sensory-frame rawlogs in (action, frame) pairs and so skips a
// sensory frame with no action before it and an action with no frame after it; the summary
// counts those separately.
TEST_P(SummaryVsRawlogEdit, SameCountsAsRawlogEditInfo) {
    const auto path = (test::mrptDatasetsDir() / GetParam()).string();
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "MRPT dataset absent: " << path;
    if (!test::haveRawlogEdit()) GTEST_SKIP() << "rawlog-edit (Debian mrpt-apps) not installed";
    registerAllClasses();
    const auto ours = inspect::summarizeRawlog(path);
    const auto theirs = test::rawlogEditInfo(path);
    ASSERT_FALSE(ours.error) << *ours.error;
    EXPECT_EQ(static_cast<long>(ours.entries - ours.unpairedActions), theirs.objects);
    ASSERT_EQ(ours.sensors.size(), theirs.occurrences.size());
    for (const auto& [label, stats] : ours.sensors) {
        ASSERT_TRUE(theirs.occurrences.count(label)) << "label '" << label << "'";
        EXPECT_EQ(static_cast<long>(stats.count - stats.inUnpairedFrames),
                  theirs.occurrences.at(label))
            << "label '" << label << "'";
    }
}

INSTANTIATE_TEST_SUITE_P(
    StockDatasets, SummaryVsRawlogEdit,
    ::testing::Values("test_rtk_path.rawlog",
                      "2006-01ENE-21-SENA_Telecom Faculty_one_loop_only.rawlog",
                      "kf-slam_6D_demo.rawlog"),
    [](const auto& info) {
        std::string n = info.param.substr(0, 12);
        for (auto& c : n) c = std::isalnum(c) ? c : '_';
        return n;
    });

TEST(RawlogSummary, RatesGapsAndCountsOfAKnownDrive) {
    registerAllClasses();
    test::TempDir dir;
    const auto path = dir.file("drive.rawlog");
    test::SampleDriveOptions options;
    options.duration = 4.0;
    auto drive = test::makeSampleDrive(options);
    // Drop 0.3 s of magnetometer MAG_LEFT to make a known gap.
    drive.erase(std::remove_if(drive.begin(), drive.end(),
                               [&](const auto& o) {
                                   const double t =
                                       mrpt::Clock::toDouble(o->timestamp) - options.t0;
                                   return o->sensorLabel == "MAG_LEFT" && t > 1.005 && t < 1.295;
                               }),
                drive.end());
    test::writeRawlog(path, drive, 1);
    const auto s = inspect::summarizeRawlog(path);
    ASSERT_FALSE(s.error);
    EXPECT_TRUE(s.compressed);
    EXPECT_EQ(s.entries, drive.size());
    EXPECT_EQ(s.format, io::RawlogFormat::Observations);
    const auto& right = s.sensors.at("MAG_RIGHT");
    EXPECT_EQ(right.count, 401u);
    EXPECT_NEAR(right.meanRate(), 100.0, 1e-6);
    EXPECT_NEAR(right.largestGap, 0.01, 1e-6);
    const auto& left = s.sensors.at("MAG_LEFT");
    EXPECT_NEAR(left.largestGap, 0.30, 1e-6);
    EXPECT_EQ(s.sensors.at("RGBD").count, 21u);
    EXPECT_NEAR(s.sensors.at("WHEELS").meanRate(), 50.0, 1e-6);
    EXPECT_EQ(s.observationClasses.at("lodestone::obs::CObservationMagnetometer"),
              401u + left.count);
}

TEST(RawlogSummary, CorruptFileGivesThePartialSummaryAndTheError) {
    registerAllClasses();
    test::TempDir dir;
    const auto path = dir.file("cut.rawlog");
    test::writeRawlog(path, test::makeSampleDrive({1.0}));
    const auto bytes = test::readBytes(path);
    test::writeBytes(path, bytes.substr(0, bytes.size() - 100));
    const auto s = inspect::summarizeRawlog(path);
    ASSERT_TRUE(s.error);
    EXPECT_NE(s.error->find(path), std::string::npos);
    EXPECT_GT(s.entries, 0u);
}
