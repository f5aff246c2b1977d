// PassNoiseEstimate: the pass-to-pass noise learnt from matched windows, from a wide prior.
#include <gtest/gtest.h>
#include <lodestone/magnetic/PassNoiseEstimate.h>

#include <cmath>
#include <random>

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
