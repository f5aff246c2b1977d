// RGB-D frames prepared ahead on another thread (lodestone-slam's decode-ahead workers) are the
// frames the odometry would prepare itself; what is not prepared ahead, dropped, or bad is
// prepared - or fails - when taken, as it always did.
#include <gtest/gtest.h>
#include <lodestone/odometry/PreparedFrames.h>
#include <lodestone/vision/RgbdVisualOdometry.h>

#include <atomic>
#include <stdexcept>
#include <thread>

#include "SampleObservations.h"

using namespace lodestone;

namespace {
vision::RgbdVisualOdometry depthAligningVo() {
    vision::RgbdVisualOdometry::Params p;
    p.depthAlignment = true;  // (its frames carry a depth cloud too)
    return vision::RgbdVisualOdometry(p);
}
}  // namespace

TEST(PreparedFrames, AFramePreparedAheadIsTheFramePreparedWhenTaken) {
    const auto vo = depthAligningVo();
    const auto prepare = [&vo](vision::RgbdFrame f) { return vo.prepare(std::move(f)); };
    odometry::PreparedFrames ahead(prepare), here(prepare);
    ahead.setCapacity(4);
    const auto scan = test::makeRangeScan(1.0, 640, 480, 3.0);
    cv::Mat texture(480, 640, CV_8UC3);
    cv::randu(texture, 0, 255);  // (corners everywhere, at the wall's depth)
    scan->intensityImage = mrpt::img::CImage(texture, mrpt::img::DEEP_COPY);
    std::thread worker([&] { ahead.prepareAhead(scan); });
    worker.join();
    const vision::PreparedFrame a = ahead.take(*scan), b = here.take(*scan);
    EXPECT_EQ(ahead.counts().ahead, 1u);
    EXPECT_EQ(ahead.counts().here, 0u);
    EXPECT_EQ(here.counts().here, 1u);
    ASSERT_GT(a.features.size(), 100u);
    ASSERT_EQ(a.features.size(), b.features.size());
    EXPECT_EQ(cv::norm(a.features.descriptors, b.features.descriptors, cv::NORM_INF), 0.0);
    EXPECT_EQ(a.features.points, b.features.points);
    ASSERT_TRUE(a.cloud && b.cloud);
    EXPECT_EQ(a.cloud->points, b.cloud->points);
    EXPECT_EQ(a.cloud->normals, b.cloud->normals);
    EXPECT_EQ(cv::norm(a.frame.gray, b.frame.gray, cv::NORM_INF), 0.0);
    // Taken once: the same observation again is prepared anew.
    ahead.take(*scan);
    EXPECT_EQ(ahead.counts().here, 1u);
}

TEST(PreparedFrames, BeyondItsCapacityOrAnotherCameraNothingWaits) {
    std::atomic<int> prepared{0};
    odometry::PreparedFrames frames([&](vision::RgbdFrame f) {
        ++prepared;
        vision::PreparedFrame p;
        p.frame = std::move(f);
        return p;
    });
    const auto first = test::makeRangeScan(1.0, 16, 12, 1.0);
    frames.prepareAhead(first);  // (no capacity yet: no reader prepares ahead)
    EXPECT_EQ(prepared, 0);
    frames.setCapacity(2);
    const auto second = test::makeRangeScan(1.1, 16, 12, 1.0), third = test::makeRangeScan(1.2, 16, 12, 1.0);
    for (const auto& s : {first, second, third}) frames.prepareAhead(s);
    EXPECT_EQ(prepared, 3);
    EXPECT_EQ(frames.counts().dropped, 1u);
    frames.take(*first);  // dropped: prepared again
    frames.take(*second);
    frames.take(*third);
    EXPECT_EQ(prepared, 4);
    EXPECT_EQ(frames.counts().ahead, 2u);
    EXPECT_EQ(frames.counts().here, 1u);
    frames.onlyCamera("OTHER");
    frames.prepareAhead(test::makeRangeScan(1.3, 16, 12, 1.0));  // (labelled RGBD)
    EXPECT_EQ(prepared, 4);
}

TEST(PreparedFrames, ARangeImageThatIsNotDepthFailsWhenTaken) {
    odometry::PreparedFrames frames([](vision::RgbdFrame f) {
        vision::PreparedFrame p;
        p.frame = std::move(f);
        return p;
    });
    frames.setCapacity(2);
    auto scan = test::makeRangeScan(1.0, 16, 12, 1.0);
    scan->range_is_depth = false;
    frames.prepareAhead(scan);  // (the worker meets the error and leaves it)
    EXPECT_THROW(frames.take(*scan), std::invalid_argument);
    EXPECT_EQ(frames.counts().ahead, 0u);
}
