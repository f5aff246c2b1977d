#include <gtest/gtest.h>
#include <lodestone/vision/DescriptorMatcher.h>
#include <lodestone/vision/GuidedMatcher.h>

#include <random>

using namespace lodestone::vision;

namespace {

const CameraIntrinsics kCamera{570.3, 570.3, 319.5, 239.5, 640, 480};

cv::Point2f project(const Eigen::Vector3d& p) {
    return {static_cast<float>(kCamera.fx * p.x() / p.z() + kCamera.cx),
            static_cast<float>(kCamera.fy * p.y() / p.z() + kCamera.cy)};
}

bool inImage(const cv::Point2f& u) {
    return u.x >= 0 && u.y >= 0 && u.x < kCamera.width && u.y < kCamera.height;
}

/** A reference frame of random textured points 1-4 m ahead, and the current frame seen after
 * `motion` (its pose in the reference): the same points (0.5 px noise, 3 descriptor bits
 * flipped) plus random distractors, shuffled. `truth[i]` is the reference index of current
 * keypoint i, -1 for a distractor. */
struct FramePair {
    FrameFeatures reference, current;
    std::vector<int> truth;
};

void addFeature(FrameFeatures& f, const cv::Point2f& u, const cv::Mat& descriptor,
                const Eigen::Vector3f& point, int octave = 0) {
    cv::KeyPoint kp(u, 31.f);
    kp.octave = octave;
    f.keypoints.push_back(kp);
    f.descriptors.push_back(descriptor);
    f.points.conservativeResize(3, f.points.cols() + 1);
    f.points.col(f.points.cols() - 1) = point;
}

FramePair makePair(const Eigen::Isometry3d& motion, int n, int distractors, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> ux(-1.5, 1.5), uz(1.0, 4.0);
    std::uniform_int_distribution<int> byte(0, 255), bit(0, 255);
    std::normal_distribution<float> pixel(0.f, 0.5f);
    FramePair fp;
    std::vector<std::pair<cv::Point2f, cv::Mat>> cur;
    std::vector<int> truth;
    const Eigen::Isometry3d T_cur_ref = motion.inverse();
    while (static_cast<int>(fp.reference.size()) < n) {
        const double z = uz(rng);
        const Eigen::Vector3d p(ux(rng) * z / 1.5 * 0.55, ux(rng) * z / 1.5 * 0.4, z);
        const cv::Point2f u = project(p);
        if (!inImage(u)) continue;
        cv::Mat d(1, 32, CV_8U);
        for (int b = 0; b < 32; ++b) d.at<std::uint8_t>(0, b) = static_cast<std::uint8_t>(byte(rng));
        const int j = static_cast<int>(fp.reference.size());
        addFeature(fp.reference, u, d, p.cast<float>());
        const Eigen::Vector3d q = T_cur_ref * p;
        const cv::Point2f v = project(q) + cv::Point2f(pixel(rng), pixel(rng));
        if (q.z() <= 0 || !inImage(v)) continue;
        cv::Mat e = d.clone();
        for (int k = 0; k < 3; ++k) {
            const int b = bit(rng);
            e.at<std::uint8_t>(0, b / 8) ^= static_cast<std::uint8_t>(1 << (b % 8));
        }
        cur.emplace_back(v, e);
        truth.push_back(j);
    }
    std::uniform_real_distribution<float> px(0.f, 639.f), py(0.f, 479.f);
    for (int k = 0; k < distractors; ++k) {
        cv::Mat d(1, 32, CV_8U);
        for (int b = 0; b < 32; ++b) d.at<std::uint8_t>(0, b) = static_cast<std::uint8_t>(byte(rng));
        cur.emplace_back(cv::Point2f(px(rng), py(rng)), d);
        truth.push_back(-1);
    }
    std::vector<int> order(cur.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::shuffle(order.begin(), order.end(), rng);
    for (int i : order) {
        addFeature(fp.current, cur[static_cast<std::size_t>(i)].first,
                   cur[static_cast<std::size_t>(i)].second, Eigen::Vector3f(0, 0, 2));
        fp.truth.push_back(truth[static_cast<std::size_t>(i)]);
    }
    return fp;
}

Eigen::Isometry3d forwardAndTurn(double forward, double yawLeft) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(-yawLeft, Eigen::Vector3d::UnitY()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(0, 0, forward);
    return T;
}

/** A wheel-like prior: 1 cm and 1 deg (1 sigma) on every axis. */
MotionPrior priorAt(const Eigen::Isometry3d& T) {
    MotionPrior p;
    p.T_ref_cur = T;
    p.covariance.setZero();
    p.covariance.diagonal() << std::pow(M_PI / 180, 2), std::pow(M_PI / 180, 2),
        std::pow(M_PI / 180, 2), 1e-4, 1e-4, 1e-4;
    return p;
}

int wrongMatches(const std::vector<cv::DMatch>& matches, const std::vector<int>& truth) {
    int wrong = 0;
    for (const auto& m : matches) wrong += truth[static_cast<std::size_t>(m.queryIdx)] != m.trainIdx;
    return wrong;
}

}  // namespace

TEST(GuidedMatcher, APriorThatSaysNothingGivesTheBruteForceMatches) {
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        const auto fp = makePair(forwardAndTurn(0.08, 0.05), 300, 300, seed);
        MotionPrior vague;
        vague.covariance = Eigen::Matrix<double, 6, 6>::Identity() * 1e4;
        for (const double ratio : {0.0, 0.8}) {
            DescriptorMatcher::Params mp;
            mp.ratio = ratio;
            GuidedMatcher::Params gp;
            gp.ratio = ratio;
            const auto brute = DescriptorMatcher(mp).match(fp.current.descriptors,
                                                           fp.reference.descriptors);
            const auto guided = GuidedMatcher(gp).match(fp.current, fp.reference, kCamera, vague);
            ASSERT_EQ(guided.matches.size(), brute.size()) << "seed " << seed;
            for (std::size_t k = 0; k < brute.size(); ++k) {
                EXPECT_EQ(guided.matches[k].queryIdx, brute[k].queryIdx);
                EXPECT_EQ(guided.matches[k].trainIdx, brute[k].trainIdx);
                EXPECT_EQ(guided.matches[k].distance, brute[k].distance);
            }
            EXPECT_EQ(guided.compared, fp.current.size() * fp.reference.size());
        }
    }
}

TEST(GuidedMatcher, AGoodPriorFindsTheCorrespondencesComparingFewPairs) {
    const auto motion = forwardAndTurn(0.10, 0.06);
    const auto fp = makePair(motion, 500, 300, 7);
    const auto r = GuidedMatcher({}).match(fp.current, fp.reference, kCamera, priorAt(motion));
    int visible = 0;
    for (int t : fp.truth) visible += t >= 0;
    EXPECT_EQ(wrongMatches(r.matches, fp.truth), 0);
    EXPECT_GE(static_cast<int>(r.matches.size()), visible * 95 / 100) << visible << " visible";
    EXPECT_LT(r.compared, fp.current.size() * fp.reference.size() / 20);
}

TEST(GuidedMatcher, ThePriorsErrorWidensTheGate) {
    // The prior 3 cm and 5 deg off the truth (50 px): outside a 1 cm / 1 deg prior's gate
    // (about 40 px), inside a 3 cm / 3 deg one (about 100 px).
    const auto motion = forwardAndTurn(0.10, 0.06);
    const auto fp = makePair(motion, 500, 300, 8);
    Eigen::Isometry3d guess = motion;
    guess.translation() += Eigen::Vector3d(0.03, 0, 0);
    guess.linear() = guess.linear() * Eigen::AngleAxisd(5 * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix();
    auto wide = priorAt(guess);
    wide.covariance.diagonal() << std::pow(3 * M_PI / 180, 2), std::pow(3 * M_PI / 180, 2),
        std::pow(3 * M_PI / 180, 2), 9e-4, 9e-4, 9e-4;
    const auto narrowMatches = GuidedMatcher({}).match(fp.current, fp.reference, kCamera, priorAt(guess));
    const auto wideMatches = GuidedMatcher({}).match(fp.current, fp.reference, kCamera, wide);
    int visible = 0;
    for (int t : fp.truth) visible += t >= 0;
    EXPECT_EQ(wrongMatches(wideMatches.matches, fp.truth), 0);
    EXPECT_GE(static_cast<int>(wideMatches.matches.size()), visible * 95 / 100);
    EXPECT_LT(narrowMatches.matches.size(), wideMatches.matches.size() / 2);
}

TEST(GuidedMatcher, RepeatedTextureIsToldApartByWhereItShouldBe) {
    // Every true keypoint has a twin 80 px to its left with the same descriptor (a brick wall's
    // repeated corner). Brute force cannot tell them apart; a gate narrower than the period can
    // (1 cm / 1 deg: about 40 px; a twin inside the gate is as ambiguous as to brute force).
    const auto motion = forwardAndTurn(0.05, 0.02);
    auto fp = makePair(motion, 300, 0, 11);
    FrameFeatures twinned;
    std::vector<int> truth;
    for (std::size_t i = 0; i < fp.current.size(); ++i) {
        const auto& kp = fp.current.keypoints[i];
        addFeature(twinned, kp.pt - cv::Point2f(80.f, 0.f), fp.current.descriptors.row(static_cast<int>(i)),
                   Eigen::Vector3f(0, 0, 2));
        truth.push_back(-1);
        addFeature(twinned, kp.pt, fp.current.descriptors.row(static_cast<int>(i)), Eigen::Vector3f(0, 0, 2));
        truth.push_back(fp.truth[i]);
    }
    const auto brute = DescriptorMatcher().match(twinned.descriptors, fp.reference.descriptors);
    const auto guided = GuidedMatcher({}).match(twinned, fp.reference, kCamera, priorAt(motion));
    EXPECT_GT(wrongMatches(brute, truth), static_cast<int>(brute.size()) / 2)
        << "brute force keeps the first of two equal twins";
    EXPECT_EQ(wrongMatches(guided.matches, truth), 0);
    EXPECT_GE(guided.matches.size(), fp.current.size() * 95 / 100);
}

TEST(GuidedMatcher, APriorFarFromTheTruthFindsAlmostNothing) {
    const auto motion = forwardAndTurn(0.10, 0.06);
    const auto fp = makePair(motion, 500, 300, 9);
    Eigen::Isometry3d wrong = motion;
    wrong.translation() += Eigen::Vector3d(0.30, 0, 0);  // 30 cm sideways: a slip, a push
    const auto r = GuidedMatcher({}).match(fp.current, fp.reference, kCamera, priorAt(wrong));
    EXPECT_LT(r.matches.size(), 15u) << "fewer than RANSAC's minimum: VO falls back to brute force";
}

TEST(GuidedMatcher, NoFeaturesNoMatches) {
    const auto fp = makePair(forwardAndTurn(0.1, 0), 50, 0, 3);
    EXPECT_TRUE(GuidedMatcher({}).match(FrameFeatures{}, fp.reference, kCamera, priorAt({})).matches.empty());
    EXPECT_TRUE(GuidedMatcher({}).match(fp.current, FrameFeatures{}, kCamera, priorAt({})).matches.empty());
}
