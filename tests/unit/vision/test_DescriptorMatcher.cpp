#include <gtest/gtest.h>
#include <lodestone/vision/DescriptorMatcher.h>

#include <opencv2/features2d.hpp>
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

namespace {
// OpenCV's BFMatcher with the same gates: the reference the packed kernel must equal.
std::vector<cv::DMatch> withOpenCv(const cv::Mat& q, const cv::Mat& t, const DescriptorMatcher::Params& p) {
    std::vector<cv::DMatch> out;
    if (p.ratio <= 0) {
        std::vector<cv::DMatch> all;
        cv::BFMatcher(cv::NORM_HAMMING, p.crossCheck).match(q, t, all);
        for (const auto& m : all)
            if (m.distance <= p.maxDistance) out.push_back(m);
        return out;
    }
    cv::BFMatcher m(cv::NORM_HAMMING, false);
    std::vector<std::vector<cv::DMatch>> knn;
    m.knnMatch(q, t, knn, 2);
    std::vector<cv::DMatch> back;
    m.match(t, q, back);
    for (const auto& k : knn) {
        if (k.empty() || k[0].distance > p.maxDistance) continue;
        if (k.size() > 1 && k[0].distance >= p.ratio * k[1].distance) continue;
        if (p.crossCheck && back[static_cast<std::size_t>(k[0].trainIdx)].trainIdx != k[0].queryIdx) continue;
        out.push_back(k[0]);
    }
    return out;
}

// Half the rows near-copies of the other set's (a few bits flipped), half unrelated; many
// equal distances, as real frames have.
std::pair<cv::Mat, cv::Mat> overlappingSets(int nq, int nt, int bytes, unsigned seed) {
    std::mt19937 rng(seed);
    cv::Mat q(nq, bytes, CV_8UC1), t(nt, bytes, CV_8UC1);
    cv::randu(q, 0, 256);
    cv::randu(t, 0, 256);
    for (int i = 0; i < std::min(nq, nt) / 2; ++i) {
        const int j = static_cast<int>(rng() % static_cast<unsigned>(nt));
        q.row(i).copyTo(t.row(j));
        for (int f = 0; f < static_cast<int>(rng() % 12); ++f)
            t.at<uchar>(j, static_cast<int>(rng() % static_cast<unsigned>(bytes))) ^= static_cast<uchar>(1u << (rng() % 8));
    }
    return {q, t};
}
}  // namespace

TEST(DescriptorMatcher, PackedKernelGivesExactlyWhatOpenCvGives) {
    for (unsigned seed = 1; seed <= 6; ++seed) {
        cv::setRNGSeed(static_cast<int>(seed));
        for (const int bytes : {32, 8, 64}) {
            const auto [q, t] = overlappingSets(300 + 37 * static_cast<int>(seed), 500, bytes, seed);
            for (const double ratio : {0.0, 0.8}) {
                for (const bool cross : {true, false}) {
                    for (const int gate : {64, 256}) {
                        DescriptorMatcher::Params p;
                        p.ratio = ratio;
                        p.crossCheck = cross;
                        p.maxDistance = std::min(gate, bytes * 8);
                        const auto ours = DescriptorMatcher(p).match(q, t);
                        const auto ref = withOpenCv(q, t, p);
                        ASSERT_EQ(ours.size(), ref.size()) << "seed " << seed << " bytes " << bytes
                                                           << " ratio " << ratio << " cross " << cross;
                        for (std::size_t k = 0; k < ours.size(); ++k) {
                            EXPECT_EQ(ours[k].queryIdx, ref[k].queryIdx);
                            EXPECT_EQ(ours[k].trainIdx, ref[k].trainIdx);
                            EXPECT_EQ(ours[k].distance, ref[k].distance);
                        }
                    }
                }
            }
        }
    }
}
