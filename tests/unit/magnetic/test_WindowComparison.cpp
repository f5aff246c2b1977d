#include <gtest/gtest.h>
#include <lodestone/magnetic/WindowComparison.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <random>

using namespace lodestone::magnetic;

namespace {

/** A smooth 3-component field along 10 m of path, every 0.05 m, seen facing `yaw` (its
 * horizontal part turned into the walker's frame), read from `from` to `to`. */
std::vector<TrackSample> walk(double from, double to, double yaw, double noise = 0,
                              unsigned seed = 1) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g(0, 1);
    std::vector<TrackSample> out;
    const double dir = to > from ? 1 : -1;
    const double c = std::cos(yaw), s = std::sin(yaw);
    for (double x = from; dir * (to - x) > 1e-9; x += dir * 0.05) {
        const double bx = 20 + 5 * std::sin(3.1 * x) + 2 * std::cos(7.3 * x);
        const double by = 4 * std::cos(2.3 * x + 1);
        const double bz = -40 + 6 * std::sin(4.7 * x + 0.5);
        TrackSample t;
        t.value =
            Eigen::Vector3f(float(c * bx + s * by + noise * g(rng)),
                            float(-s * bx + c * by + noise * g(rng)), float(bz + noise * g(rng)));
        t.s = std::abs(x - from);
        out.push_back(t);
    }
    return out;
}

const PassNoise kNoise{1.0, 0, 0, 0.05};

std::vector<TrackSample> join(std::vector<TrackSample> a, const std::vector<TrackSample>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

}  // namespace

TEST(WindowComparison, TheSamePlaceWalkedAgainFitsWithNoTurn) {
    // Two passes east; the second's window [4, 5) m against the first's.
    const auto s = join(walk(0, 10, 0), walk(0, 10, 0.2));  // the second pass faces 0.2 rad left
    const std::size_t n = 20, first = 200 + 80, target = 80;
    const auto fit =
        compareWindows(s, first, s, target, n, WindowDirection::Forward, kNoise, 0.0, INFINITY);
    EXPECT_LT(fit.chi2, 1e-6);
    EXPECT_NEAR(fit.turn, 0.2, 1e-4);  // the field measures the relative heading
    EXPECT_LT(fit.turnVariance, 1e-3);
    // One sample off along the path no longer fits.
    EXPECT_GT(
        compareWindows(s, first, s, target + 1, n, WindowDirection::Forward, kNoise, 0, INFINITY)
            .chi2,
        1.0);
    // A heading prior held far from the field's turn leaves a misfit.
    const auto held =
        compareWindows(s, first, s, target, n, WindowDirection::Forward, kNoise, 0.0, 1e-6);
    EXPECT_GT(held.chi2, 100.0);
    EXPECT_LT(std::abs(held.turn), 0.01);
}

TEST(WindowComparison, ThePlaceWalkedBackFitsReversedAndTurnedByHalfATurn) {
    // East, then back west: the west pass at 6 -> 5 m read against the east pass's [5, 6).
    const auto s = join(walk(0, 10, 0), walk(10, 0, M_PI));
    const std::size_t n = 20;
    const std::size_t first = 200 + 80;  // west pass samples at x = 6.0 ... 5.05
    const std::size_t target = 101;      // east pass samples at x = 5.05 ... 6.0
    const auto back =
        compareWindows(s, first, s, target, n, WindowDirection::Backward, kNoise, M_PI, 0.01);
    EXPECT_LT(back.chi2, 1e-6);
    EXPECT_NEAR(std::abs(back.turn), M_PI, 1e-4);
    EXPECT_GT(
        compareWindows(s, first, s, target, n, WindowDirection::Forward, kNoise, M_PI, 0.01).chi2,
        100.0);
    const auto d = windowResiduals(s, first, s, target, n, WindowDirection::Backward, back);
    EXPECT_LT(d.cwiseAbs().maxCoeff(), 1e-4);
}

TEST(WindowComparison, TheNullModelFavoursTheSamePlaceOnlyWhenTheFieldSaysSo) {
    const WindowNullModel null(20, kNoise, 3.0, 0.28);
    const auto same = join(walk(0, 10, 0, 0.5, 1), walk(0, 10, 0, 0.5, 2));
    const auto fit =
        compareWindows(same, 200 + 80, same, 80, 20, WindowDirection::Forward, kNoise, 0, INFINITY);
    EXPECT_GT(null.logLikelihoodRatio(
                  windowResiduals(same, 280, same, 80, 20, WindowDirection::Forward, fit)),
              10.0);
    // Two unrelated stretches (3 m apart) differ as the null expects: far below.
    const auto far = compareWindows(same, 200 + 80, same, 140, 20, WindowDirection::Forward, kNoise,
                                    0, INFINITY);
    EXPECT_LT(null.logLikelihoodRatio(
                  windowResiduals(same, 280, same, 140, 20, WindowDirection::Forward, far)),
              0.0);
}

TEST(WindowComparison, AnOffsetAndATrendBetweenPassesCostWhatTheirModelSays) {
    // The second pass reads 2.5 uT high on every component and drifts by 1 uT/m.
    auto s = join(walk(0, 10, 0), walk(0, 10, 0));
    for (std::size_t k = 200; k < s.size(); ++k)
        s[k].value.array() += float(2.5 + 1.0 * (s[k].s - 5.0));
    const std::size_t n = 20, first = 280, target = 80;
    const auto white =
        compareWindows(s, first, s, target, n, WindowDirection::Forward, kNoise, 0, INFINITY);
    EXPECT_GT(white.chi2, 100.0);  // white noise of 1 uT: far too big a difference
    const PassNoise smooth{1.0, 2.0, 2.0, 0.05};
    const auto fit =
        compareWindows(s, first, s, target, n, WindowDirection::Forward, smooth, 0, INFINITY);
    // An offset and a trend of their model's size cost what a constant of 2.5 uT does under
    // it: n c^2 / (sigma^2 + n bias^2), about 1.5 a component.
    EXPECT_LT(fit.chi2, 10.0);
    // The O(n) form agrees with the dense covariance.
    const Eigen::MatrixXd C = passNoiseCovariance(n, smooth);
    const auto d = windowResiduals(s, first, s, target, n, WindowDirection::Forward, fit);
    double dense = 0;
    for (int c = 0; c < 3; ++c) dense += d.col(c).dot(C.ldlt().solve(d.col(c)));
    EXPECT_NEAR(fit.chi2, dense, 1e-6 * std::max(1.0, dense));
}

TEST(WindowComparison, ExcitationAndChiSquareQuantiles) {
    std::vector<TrackSample> flat(20);
    Eigen::VectorXf earth(3);  // (dynamic size: GCC 12 warns falsely on a fixed-size copy)
    earth << 20, 0, -40;
    for (auto& t : flat) t.value = earth;
    EXPECT_NEAR(windowExcitation(flat, 0, 20, 1.0), 0.0, 1e-9);
    const auto lively = walk(0, 2, 0);
    EXPECT_GT(windowExcitation(lively, 0, 20, 1.0), chiSquareQuantile(57, 0.9973));
    // Exact for 2 dof: -2 ln(1 - p); Wilson-Hilferty within a few per cent.
    EXPECT_NEAR(chiSquareQuantile(2, 0.9973), -2 * std::log(0.0027), 0.03 * 11.83);
    EXPECT_NEAR(chiSquareQuantile(60, 0.5), 59.33, 0.1);
    EXPECT_THROW(chiSquareQuantile(0, 0.5), std::invalid_argument);
}
