#include <gtest/gtest.h>
#include <lodestone/magnetic/WindowDisplacement.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <random>

using namespace lodestone::magnetic;

namespace {

constexpr std::size_t kN = 30;
const PassNoise kNoise{1.0, 0, 0, 0.05};
constexpr double kSigmaF = 5.0, kLength = 0.28, kPrior = 0.2, kRadius = 0.5;

/** Differences of two passes `delta` apart drawn from the model's own covariance, built here
 * from its definition (not from the class under test). */
class Draws {
  public:
    explicit Draws(double delta, unsigned seed) : rng_(seed) {
        const auto m = static_cast<Eigen::Index>(kN);
        Eigen::MatrixXd C = passNoiseCovariance(kN, kNoise);
        const double rho =
            std::isinf(delta) ? 0.0 : std::exp(-0.5 * delta * delta / (kLength * kLength));
        for (Eigen::Index i = 0; i < m; ++i) {
            for (Eigen::Index j = 0; j < m; ++j) {
                const double r = double(i - j) * kNoise.step / kLength;
                C(i, j) += 2 * kSigmaF * kSigmaF * (1 - rho) * std::exp(-0.5 * r * r);
            }
        }
        L_ = C.llt().matrixL();
    }
    Eigen::MatrixX3d next() {
        Eigen::MatrixX3d z(static_cast<Eigen::Index>(kN), 3);
        for (Eigen::Index i = 0; i < z.size(); ++i) z.data()[i] = g_(rng_);
        return L_ * z;
    }

  private:
    std::mt19937 rng_;
    std::normal_distribution<double> g_{0, 1};
    Eigen::MatrixXd L_;
};

const WindowDisplacementModel& model() {
    static const WindowDisplacementModel m(kN, kNoise, kSigmaF, kLength, kPrior, kRadius);
    return m;
}

/** The posterior of "near" against "beside" and "unrelated places" at even prior odds. */
double nearPosterior(const WindowDisplacementModel::Evidence& e) {
    return 1 / (1 + std::exp(e.logFar - e.logNear) + std::exp(-e.logNear));
}

}  // namespace

TEST(WindowDisplacement, PassesOnOneLineAreNearAndBeatUnrelatedPlaces) {
    Draws draws(0.0, 1);
    int near = 0;
    for (int i = 0; i < 200; ++i) {
        const auto e = model().evidence(draws.next(), kRadius);
        near += nearPosterior(e) > 0.9973;
        EXPECT_LT(e.nearDelta2, 0.1 * 0.1);  // the field says: close together
    }
    EXPECT_GE(near, 198);
}

TEST(WindowDisplacement, UnrelatedPlacesAreNotNear) {
    Draws draws(INFINITY, 2);
    int near = 0;
    for (int i = 0; i < 1000; ++i)
        near += nearPosterior(model().evidence(draws.next(), kRadius)) > 0.9973;
    EXPECT_LE(near, 3);  // (a 0.9973 posterior: a few in 1000 by the model's own odds)
}

TEST(WindowDisplacement, APassBesideTheRadiusCountsAsFar) {
    // 0.8 m beside, in a field whose anomalies are 0.28 m wide: another stretch of field.
    Draws draws(0.8, 3);
    int near = 0;
    for (int i = 0; i < 1000; ++i)
        near += nearPosterior(model().evidence(draws.next(), kRadius)) > 0.9973;
    EXPECT_LE(near, 3);
    // 0.3 m beside: near, and the posterior distance says so.
    Draws beside(0.3, 4);
    double d2 = 0;
    for (int i = 0; i < 200; ++i) d2 += model().evidence(beside.next(), kRadius).nearDelta2 / 200;
    EXPECT_NEAR(std::sqrt(d2), 0.3, 0.08);
}

TEST(WindowDisplacement, TheFitStatisticIsChiSquareAtTheRadius) {
    // Drawn at the radius, the differences' quadratic form has mean 3n (chi-square, 3n dof).
    Draws draws(kRadius, 5);
    double mean = 0;
    for (int i = 0; i < 400; ++i)
        mean += model().evidence(draws.next(), kRadius).chi2AtRadius / 400;
    EXPECT_NEAR(mean, 3.0 * kN, 0.05 * 3 * kN);
    // ... and it is the model's chi2 there; the lower bound never exceeds it.
    const auto d = draws.next();
    EXPECT_NEAR(model().evidence(d, kRadius).chi2AtRadius, model().chi2(d, kRadius), 1e-9);
    const double white = passNoiseCovariance(kN, kNoise).llt().solve(d).cwiseProduct(d).sum();
    EXPECT_LE(model().chi2LowerBound(white, kRadius), model().chi2(d, kRadius) + 1e-9);
    // A smaller near radius (a turn) rounds down to a bin and asks for a closer pass.
    const auto e = model().evidence(d, 0.33);
    EXPECT_NEAR(e.chi2AtRadius, model().chi2(d, 0.3), 1e-9);
    EXPECT_LT(e.logNear, model().evidence(d, kRadius).logNear);
}

TEST(WindowDisplacement, UnrelatedIsTheLimitAndBadInputThrows) {
    Draws draws(0.0, 6);
    const auto d = draws.next();
    EXPECT_NEAR(model().logLikelihoodRatio(d, 1e3), 0.0, 1e-9);
    EXPECT_GT(model().logLikelihoodRatio(d, 0.0), 0.0);
    EXPECT_THROW(WindowDisplacementModel(kN, kNoise, kSigmaF, kLength, 0.0, kRadius),
                 std::invalid_argument);
    EXPECT_THROW(WindowDisplacementModel(1, kNoise, kSigmaF, kLength, kPrior, kRadius),
                 std::invalid_argument);
}

TEST(WindowDisplacement, AFinePartOnABroadOneSeparatesBesideFromUnrelated) {
    // Two scales: passes beside each other differ by a fine part of amplitude 1 uT only,
    // unrelated places by the whole 5 uT. Passes 0.8 m beside then differ little: under one
    // amplitude (5 uT for both) they look like passes on one line, under two the field cannot
    // tell them from one line and the prior on the distance keeps them short of a sure "near".
    const auto basis = std::make_shared<WindowDisplacementModel::Basis>(kN, kNoise, kLength);
    const WindowDisplacementModel twoScales(basis, 1.0, kPrior, kRadius, kSigmaF);
    const WindowDisplacementModel oneScale(basis, kSigmaF, kPrior, kRadius);
    std::mt19937 rng(7);
    std::normal_distribution<double> g(0, 1);
    const Eigen::Index m = static_cast<Eigen::Index>(kN);
    Eigen::MatrixXd C = passNoiseCovariance(kN, kNoise);
    const double rho = std::exp(-0.5 * 0.8 * 0.8 / (kLength * kLength));
    for (Eigen::Index i = 0; i < m; ++i)
        for (Eigen::Index j = 0; j < m; ++j) {
            const double r = double(i - j) * kNoise.step / kLength;
            C(i, j) += 2 * 1.0 * (1 - rho) * std::exp(-0.5 * r * r);
        }
    const Eigen::MatrixXd L = C.llt().matrixL();
    int nearTwo = 0, nearOne = 0;
    for (int k = 0; k < 200; ++k) {
        Eigen::MatrixX3d z(m, 3);
        for (Eigen::Index i = 0; i < z.size(); ++i) z.data()[i] = g(rng);
        const Eigen::MatrixX3d d = L * z;
        nearTwo += nearPosterior(twoScales.evidence(d, kRadius)) > 0.9973;
        nearOne += nearPosterior(oneScale.evidence(d, kRadius)) > 0.9973;
    }
    EXPECT_LE(nearTwo, 20);
    EXPECT_GE(nearOne, 180);
    // With the same amplitude given twice, the model is the one-amplitude model.
    const auto d = Draws(0.0, 8).next();
    const WindowDisplacementModel same(basis, kSigmaF, kPrior, kRadius, kSigmaF);
    EXPECT_NEAR(same.evidence(d, kRadius).logNear, oneScale.evidence(d, kRadius).logNear, 1e-9);
    EXPECT_THROW(WindowDisplacementModel(basis, 1.0, kPrior, kRadius, -1.0), std::invalid_argument);
}
