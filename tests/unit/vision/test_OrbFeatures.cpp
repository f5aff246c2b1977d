// ORB extraction with and without the depth mask: a high-contrast texture out of the depth
// sensor's range takes ORB's budget unless ORB is told where depth exists.
#include <gtest/gtest.h>
#include <lodestone/vision/OrbFeatures.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

using namespace lodestone::vision;

namespace {
// Random grey blocks of `contrast` over a rectangle of the image.
void blocks(cv::Mat& gray, cv::Rect area, int contrast, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> level(128 - contrast / 2, 128 + contrast / 2);
    for (int y = area.y; y < area.y + area.height; y += 6) {
        for (int x = area.x; x < area.x + area.width; x += 6) {
            gray(cv::Rect(x, y, 6, 6) & area).setTo(level(rng));
        }
    }
}

// Left half: a strong texture beyond the sensor's range (no depth); right half: a faint one at
// 2 m.
RgbdFrame farPosterNearWall() {
    RgbdFrame f;
    f.gray = cv::Mat(480, 640, CV_8UC1, cv::Scalar(128));
    blocks(f.gray, {0, 0, 320, 480}, 250, 1);
    blocks(f.gray, {320, 0, 320, 480}, 60, 2);
    f.depth = cv::Mat(480, 640, CV_32FC1, cv::Scalar(2.0f));
    f.depth(cv::Rect(0, 0, 320, 480)).setTo(std::nanf(""));
    f.intrinsics = {525, 525, 319.5, 239.5, 640, 480};
    return f;
}
}  // namespace

TEST(OrbExtractor, DepthMaskSpendsTheBudgetWhereDepthIs) {
    const RgbdFrame frame = farPosterNearWall();
    OrbExtractor::Params p;
    p.features = 200;
    const auto plain = OrbExtractor(p).extract(frame);
    p.depthMask = true;
    const auto masked = OrbExtractor(p).extract(frame);
    // Without the mask ORB keeps the strong corners, nearly all without depth: few survive.
    EXPECT_GT(plain.detected, 150u);
    EXPECT_LT(plain.size(), 60u) << "the far texture did not win: the test's premise is off";
    // With it, the whole budget lands on the near wall and every keypoint has depth.
    EXPECT_GT(masked.size(), 150u);
    EXPECT_EQ(masked.size(), masked.detected);
    for (const auto& k : masked.keypoints) EXPECT_GE(k.pt.x, 319.0f);
    for (Eigen::Index i = 0; i < masked.points.cols(); ++i) EXPECT_NEAR(masked.points(2, i), 2.0f, 1e-6);
}

TEST(OrbExtractor, DepthMaskIgnoresADepthImageOfAnotherSize) {
    // (a dataset whose depth is not registered: no mask rather than an OpenCV error)
    RgbdFrame frame = farPosterNearWall();
    cv::resize(frame.depth, frame.depth, cv::Size(320, 240), 0, 0, cv::INTER_NEAREST);
    OrbExtractor::Params p;
    p.depthMask = true;
    EXPECT_NO_THROW(OrbExtractor(p).extract(frame));
}
