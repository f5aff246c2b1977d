#include <gtest/gtest.h>
#include <lodestone/vision/DescriptorMatcher.h>

#include <random>

using namespace lodestone::vision;

namespace {
cv::Mat randomDescriptors(int n, unsigned seed) {
    cv::Mat d(n, 32, CV_8UC1);
    std::mt19937 rng(seed);
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < 32; ++j) d.at<uchar>(i, j) = static_cast<uchar>(rng() & 0xFF);
    }
    return d;
}
}  // namespace

TEST(DescriptorMatcher, FindsTheSameDescriptorsShuffledAndSlightlyChanged) {
    const cv::Mat a = randomDescriptors(300, 1);
    cv::Mat b(300, 32, CV_8UC1);
    std::mt19937 rng(2);
    for (int i = 0; i < 300; ++i) {
        a.row(i).copyTo(b.row((i * 7) % 300));  // 7 is coprime with 300: a permutation
        b.at<uchar>((i * 7) % 300, rng() % 32) ^= static_cast<uchar>(1u << (rng() % 8));  // 1 bit
    }
    for (const double ratio : {0.0, 0.8}) {
        DescriptorMatcher::Params p;
        p.ratio = ratio;
        const auto matches = DescriptorMatcher(p).match(a, b);
        ASSERT_EQ(matches.size(), 300u) << "ratio " << ratio;
        for (const auto& m : matches) {
            EXPECT_EQ(m.trainIdx, (m.queryIdx * 7) % 300);
            EXPECT_LE(m.distance, 1.0f);
        }
    }
}

TEST(DescriptorMatcher, UnrelatedDescriptorsAreGatedOut) {
    // Random 256-bit strings are ~128 bits apart; the distance gate rejects them all.
    const auto matches =
        DescriptorMatcher().match(randomDescriptors(200, 3), randomDescriptors(200, 4));
    EXPECT_TRUE(matches.empty()) << matches.size();
    EXPECT_TRUE(DescriptorMatcher().match(cv::Mat(), randomDescriptors(5, 1)).empty());
}
