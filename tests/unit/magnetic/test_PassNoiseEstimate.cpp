// PassNoiseEstimate: the pass-to-pass noise learnt from matched windows, from a wide prior.
#include <gtest/gtest.h>
#include <lodestone/magnetic/PassNoiseEstimate.h>

#include <cmath>
#include <random>
#include <vector>

using lodestone::magnetic::PassNoiseEstimate;

namespace {
/** `windows` windows of 41 readings x 3 components, each the difference of two passes whose
 * readings carry white noise of `perReading` (their difference: sqrt 2 of that). */
PassNoiseEstimate learn(double perReading, double priorSigma, int windows, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, perReading);
    PassNoiseEstimate e(priorSigma, 123);
    for (int w = 0; w < windows; ++w) {
        Eigen::MatrixX3d d(41, 3);
        for (Eigen::Index i = 0; i < d.size(); ++i) d.data()[i] = noise(rng) - noise(rng);
        e.add(d);
    }
    return e;
}
}  // namespace

TEST(PassNoiseEstimate, RecoversASimulatedRepeatabilityWithinAFifthFromAPriorTwiceOrHalfIt) {
    // Passes that differ by 0.7 uT per component (0.5 uT per reading, each pass): from a
    // prior of 1.4 or 0.35 uT worth one window, ten matched windows bring it within 20 % (the
    // prior twice the truth still weighs: 13 % over).
    const double truth = 0.5 * std::sqrt(2.0);
    for (const double prior : {2 * truth, truth / 2}) {
        for (unsigned seed = 1; seed <= 5; ++seed) {
            const auto e = learn(0.5, prior, 10, seed);
            EXPECT_NEAR(e.sigma(), truth, 0.2 * truth) << "prior " << prior << " seed " << seed;
            EXPECT_NEAR(e.dof(), 10 * (123 - 1), 1e-9);
        }
    }
}

TEST(PassNoiseEstimate, BeforeAnyMatchItIsThePriorAndBadDataIsLeftOut) {
    PassNoiseEstimate e(1.0, 123);
    EXPECT_DOUBLE_EQ(e.sigma(), 1.0);
    EXPECT_DOUBLE_EQ(e.dof(), 0.0);
    Eigen::MatrixX3d bad = Eigen::MatrixX3d::Zero(41, 3);
    bad(3, 1) = NAN;
    e.add(bad);
    EXPECT_DOUBLE_EQ(e.sigma(), 1.0);
    // Readings that repeat exactly pull it down, as far as their weight against the prior's.
    e.add(Eigen::MatrixX3d::Zero(41, 3));
    EXPECT_NEAR(e.sigma(), std::sqrt(123.0 / (123.0 + 122.0)), 1e-12);
    EXPECT_THROW(PassNoiseEstimate(0, 1), std::invalid_argument);
}

TEST(PassNoiseEstimate, AMapsOwnOverlappingPassesGiveItsRepeatabilityAndOnePassGivesNone) {
    // A field along y = 0 walked three times (0.02 m beside each time), each reading with
    // white noise of 0.6 uT per component; positions every 0.05 m.
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0, 0.6);
    std::vector<Eigen::Vector2d> p;
    std::vector<Eigen::Vector3d> f;
    std::vector<double> travel;
    std::vector<int> segment;
    double s = 0;
    for (int pass = 0; pass < 3; ++pass) {
        for (int i = 0; i < 200; ++i, s += 0.05) {
            const double x = 0.05 * i;
            p.emplace_back(x, 0.02 * pass);
            f.emplace_back(20 + 5 * std::sin(3 * x) + noise(rng), 3 * std::cos(2 * x) + noise(rng),
                           -40 + noise(rng));
            travel.push_back(s);
            segment.push_back(0);
        }
        s += 10;  // walked round to the start
    }
    const auto all = lodestone::magnetic::passRepeatabilityAcrossPasses(p, f, travel, segment,
                                                                         0.06, 1.0);
    ASSERT_TRUE(all.has_value());
    EXPECT_NEAR(*all, 0.6, 0.12);
    // One pass only: its neighbours are the same pass (within the travel gap) - none.
    const std::vector<Eigen::Vector2d> p1(p.begin(), p.begin() + 200);
    const std::vector<Eigen::Vector3d> f1(f.begin(), f.begin() + 200);
    const std::vector<double> t1(travel.begin(), travel.begin() + 200);
    const std::vector<int> s1(segment.begin(), segment.begin() + 200);
    EXPECT_FALSE(lodestone::magnetic::passRepeatabilityAcrossPasses(p1, f1, t1, s1, 0.06, 1.0));
}
