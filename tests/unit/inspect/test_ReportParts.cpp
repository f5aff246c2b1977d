// The pieces of `lodestone-inspect report` that judge a rawlog: time bins, gaps, backwards
// timestamps, wheel drops, thumbnails.
#include <gtest/gtest.h>
#include <lodestone/inspect/report/SensorTimeline.h>
#include <lodestone/inspect/report/Thumbnails.h>
#include <lodestone/inspect/report/TimeBins.h>
#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/obs/CObservationWheelDrop.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <filesystem>
#include <random>

#include "TestPaths.h"

using namespace lodestone::inspect::report;

namespace {
lodestone::obs::CObservationMagnetometer magnetometer(const std::string& label) {
    lodestone::obs::CObservationMagnetometer m;
    m.sensorLabel = label;
    m.field = {20, 0, -40};
    return m;
}
}  // namespace

TEST(TimeBins, GrowingKeepsEveryCountAndTheCapacity) {
    TimeBins<CountBin> bins(16, 0.1);
    std::size_t added = 0;
    for (double t = 0; t < 100; t += 0.05) {
        bins.at(t).count++;
        ++added;
    }
    std::size_t total = 0;
    for (std::size_t i = 0; i < bins.used(); ++i) total += bins[i].count;
    EXPECT_EQ(total, added);
    EXPECT_LE(bins.used(), 16u);
    EXPECT_GE(bins.width() * 16, 100.0);  // the last time fits
    EXPECT_LT(bins.width() * 8, 100.0);   // and the width doubled no more than needed
}

TEST(TimeBins, EnvelopeMergesMinMaxAndMean) {
    TimeBins<EnvelopeBin> bins(4, 1.0);
    bins.at(0.5).add(1.0);
    bins.at(1.5).add(5.0);
    bins.at(7.5).add(3.0);  // doubles the width: 0.5 and 1.5 share a bin now
    EXPECT_DOUBLE_EQ(bins.width(), 2.0);
    EXPECT_DOUBLE_EQ(bins[0].min, 1.0);
    EXPECT_DOUBLE_EQ(bins[0].max, 5.0);
    EXPECT_DOUBLE_EQ(bins[0].mean(), 3.0);
    EXPECT_EQ(bins[3].count, 1u);
}

TEST(TimelineBuilder, FindsTheGapAndTheBackwardsTimestampOfA100HzSensor) {
    TimelineBuilder b;
    auto m = magnetometer("MAG");
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(-0.003, 0.003);  // +-30 % of the period
    for (int i = 0; i < 1000; ++i) {
        const double t = 0.01 * i;
        if (t >= 4.0 && t < 5.0) continue;  // a second missing
        b.add(m, t + jitter(rng));
        if (i == 700) b.add(m, 6.7);  // 0.3 s older than the newest
    }
    const auto tl = b.finish();
    ASSERT_EQ(tl.size(), 1u);
    EXPECT_EQ(tl[0].count, 901u);
    EXPECT_NEAR(tl[0].medianStep, 0.01, 0.001);
    ASSERT_EQ(tl[0].gapCount, 1u);
    EXPECT_NEAR(tl[0].gaps[0].time, 3.99, 0.01);
    EXPECT_NEAR(tl[0].gaps[0].size, 1.01, 0.01);
    ASSERT_EQ(tl[0].backwardCount, 1u);
    EXPECT_NEAR(tl[0].backwards[0].size, 0.3, 0.01);
}

TEST(TimelineBuilder, ASlowSteadySensorHasNoGapsAndAnEventSensorNone) {
    TimelineBuilder b;
    auto slow = magnetometer("SLOW");
    lodestone::obs::CObservationWheelDrop drop;
    drop.sensorLabel = "DROP";
    for (int i = 0; i < 100; ++i) b.add(slow, 0.5 * i);  // 2 Hz, 50 s
    drop.leftDropped = true;
    b.add(drop, 3.0);
    drop.leftDropped = false;
    b.add(drop, 40.0);  // 37 s later: not a gap for an event sensor
    const auto tl = b.finish();
    ASSERT_EQ(tl.size(), 2u);
    EXPECT_EQ(tl[0].label, "DROP");
    EXPECT_TRUE(tl[0].eventDriven);
    EXPECT_EQ(tl[0].gapCount, 0u);
    ASSERT_EQ(tl[0].wheelDrops.size(), 2u);
    EXPECT_TRUE(tl[0].wheelDrops[0].second);
    EXPECT_FALSE(tl[0].wheelDrops[1].second);
    EXPECT_EQ(tl[1].gapCount, 0u);
}

TEST(TimelineBuilder, WouldBeGapWhileStreaming) {
    TimelineBuilder b;
    auto m = magnetometer("MAG");
    for (int i = 0; i < 50; ++i) b.add(m, 0.01 * i);
    EXPECT_FALSE(b.wouldBeGap("MAG", 0.50));
    EXPECT_TRUE(b.wouldBeGap("MAG", 0.80));
    EXPECT_FALSE(b.wouldBeGap("OTHER", 10.0));
}

TEST(ThumbnailSampler, EveryNSecondsAndBothSidesOfAGap) {
    lodestone::test::TempDir dir;
    ThumbnailOptions o;
    o.every = 10;
    ThumbnailSampler sampler(dir.path(), "thumbs", o);
    auto frameAt = [](double) {
        auto scan = mrpt::obs::CObservation3DRangeScan::Create();
        scan->sensorLabel = "RGBD";
        scan->hasRangeImage = true;
        scan->rangeImage.setConstant(24, 32, 1500);
        scan->rangeImage(0, 0) = 0;  // no depth there: black
        scan->hasIntensityImage = true;
        scan->intensityImage.resize(32, 24, mrpt::img::CH_RGB);
        return scan;
    };
    for (int i = 0; i < 60; ++i) {  // 2 Hz for 30 s, a gap from 20 s to 25 s
        const double t = 0.5 * i;
        if (t > 20 && t < 25) continue;
        sampler.add(frameAt(t), t, t == 25.0);
    }
    std::vector<std::string> why;
    for (const auto& t : sampler.thumbnails()) why.push_back(t.why + "@" + std::to_string(int(t.time)));
    const std::vector<std::string> expected = {"every 10 s@0", "every 10 s@10", "every 10 s@20",
                                               "after a gap@25"};
    // 20 s was taken as a regular thumbnail, so "before a gap" does not repeat it.
    EXPECT_EQ(why, expected);
    for (const auto& t : sampler.thumbnails()) {
        EXPECT_TRUE(std::filesystem::exists(dir.path() / t.rgb)) << t.rgb;
        EXPECT_TRUE(std::filesystem::exists(dir.path() / t.depth)) << t.depth;
    }
}
