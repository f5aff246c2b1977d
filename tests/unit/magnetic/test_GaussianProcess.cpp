// The GP of paper 000 eq. (3): its marginal-likelihood gradient, the shift scan, and the
// hyperparameter fit.
#include <gtest/gtest.h>
#include <lodestone/magnetic/GaussianProcess1D.h>
#include <lodestone/magnetic/GpShiftCorrection.h>
#include <lodestone/magnetic/HyperparameterFit.h>

#include <Eigen/Cholesky>

#include "SyntheticField.h"

using namespace lodestone::magnetic;

namespace {
// Readings of `field` at s in [from, to) every `step`, with Gaussian noise.
void sample(const lodestone::test::SyntheticField& field, double from, double to, double step,
            double noise, unsigned seed, std::vector<double>& s, Eigen::MatrixXd& Y,
            double offset = 0) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0, noise);
    s.clear();
    for (double x = from; x < to; x += step) s.push_back(x);
    Y.resize(static_cast<Eigen::Index>(s.size()), 2);
    for (std::size_t i = 0; i < s.size(); ++i) {
        const auto v = field.at(s[i] + offset);
        Y(static_cast<Eigen::Index>(i), 0) = v[0] + n(rng);
        Y(static_cast<Eigen::Index>(i), 1) = v[1] + n(rng);
    }
}
}  // namespace

TEST(GaussianProcess1D, MarginalLikelihoodGradientMatchesNumericalDifferences) {
    const lodestone::test::SyntheticField field(4);
    std::vector<double> s;
    Eigen::MatrixXd Y;
    sample(field, 0, 3, 0.05, 0.3, 1, s, Y);
    const GpHyperparameters h{3.0, 0.35, 0.4, 5.0};
    Eigen::Vector4d g;
    GaussianProcess1D::logMarginal(s, Y, h, &g);
    const double e = 1e-5;
    for (int k = 0; k < 4; ++k) {
        GpHyperparameters up = h, down = h;
        double* pu[4] = {&up.sigmaF, &up.lengthScale, &up.sigmaN, &up.sigmaC};
        double* pd[4] = {&down.sigmaF, &down.lengthScale, &down.sigmaN, &down.sigmaC};
        *pu[k] *= std::exp(e);  // derivative in log space
        *pd[k] *= std::exp(-e);
        const double numeric = (GaussianProcess1D::logMarginal(s, Y, up) -
                                GaussianProcess1D::logMarginal(s, Y, down)) /
                               (2 * e);
        EXPECT_NEAR(g[k], numeric, 1e-4 * std::max(1.0, std::abs(numeric))) << "parameter " << k;
    }
}

TEST(GaussianProcess1D, InterpolatesTheFieldBetweenReadings) {
    const lodestone::test::SyntheticField field(5);
    std::vector<double> s;
    Eigen::MatrixXd Y;
    sample(field, 0, 4, 0.05, 0.2, 2, s, Y);
    GaussianProcess1D gp({4.0, 0.3, 0.2, 10.0});
    gp.fit(s, Y);
    Eigen::MatrixXd mean;
    Eigen::VectorXd var;
    gp.predict({1.0125, 2.5375}, mean, var);
    EXPECT_NEAR(mean(0, 0), field.at(1.0125)[0], 0.3);
    EXPECT_NEAR(mean(1, 1), field.at(2.5375)[1], 0.3);
    EXPECT_LT(var[0], 0.1);
}

TEST(GpShiftCorrection, RecoversAKnownAlongPathOffsetWithin2cm) {
    for (const double truth : {0.137, -0.262, 0.0, 0.41}) {
        const lodestone::test::SyntheticField field(6);
        std::vector<double> ts, qs;
        Eigen::MatrixXd T, Q;
        sample(field, 0, 6, 0.05, 0.3, 3, ts, T);
        // The query saw the field `truth` metres further along than its travel says.
        sample(field, 1.5, 4.5, 0.05, 0.3, 4, qs, Q, truth);
        GaussianProcess1D gp({4.0, 0.3, 0.3, 10.0});
        gp.fit(ts, T);
        const auto r = scanShift(gp, qs, Q, ShiftScanParams{0.5, 0.02, 0.01});
        ASSERT_TRUE(r.valid) << truth;
        EXPECT_NEAR(r.shift, truth, 0.02) << truth;
        EXPECT_LT(r.sigma, 0.05);
        EXPECT_LT(r.normalizedRms, 1.5) << truth;
    }
}

TEST(GpShiftCorrection, AFieldWithNoMatchingPlaceFitsBadly) {
    const lodestone::test::SyntheticField field(7), other(8);
    std::vector<double> ts, qs;
    Eigen::MatrixXd T, Q;
    sample(field, 0, 6, 0.05, 0.3, 5, ts, T);
    sample(other, 1.5, 4.5, 0.05, 0.3, 6, qs, Q);
    GaussianProcess1D gp({4.0, 0.3, 0.3, 10.0});
    gp.fit(ts, T);
    const auto r = scanShift(gp, qs, Q, ShiftScanParams{0.5, 0.02, 0.01});
    EXPECT_TRUE(!r.valid || r.normalizedRms > 2.0) << r.normalizedRms;  // the ERD's gate is 2
}

TEST(HyperparameterFit, RecoversTheLengthScaleOfGpSampledFields) {
    // Stretches drawn from the GP prior itself (length scale 0.4 m, sigma_f 3, noise 0.3).
    const GpHyperparameters truth{3.0, 0.4, 0.3, 1.0};
    std::mt19937 rng(11);
    std::normal_distribution<double> n(0, 1);
    std::vector<FieldStretch> stretches;
    for (int k = 0; k < 8; ++k) {
        FieldStretch f;
        for (double s = 0; s < 5; s += 0.05) f.travel.push_back(s);
        const auto N = static_cast<Eigen::Index>(f.travel.size());
        Eigen::MatrixXd K(N, N);
        for (Eigen::Index i = 0; i < N; ++i) {
            for (Eigen::Index j = 0; j < N; ++j) {
                const double d = (f.travel[i] - f.travel[j]) / truth.lengthScale;
                K(i, j) = truth.sigmaF * truth.sigmaF * std::exp(-0.5 * d * d) + (i == j) * 1e-8;
            }
        }
        const Eigen::MatrixXd L = K.llt().matrixL();
        f.readings.resize(N, 2);
        for (int c = 0; c < 2; ++c) {
            Eigen::VectorXd z(N), e(N);
            for (Eigen::Index i = 0; i < N; ++i) {
                z[i] = n(rng);
                e[i] = truth.sigmaN * n(rng);
            }
            f.readings.col(c) = L * z + e;
        }
        stretches.push_back(f);
    }
    const auto r = fitHyperparameters(stretches, GpHyperparameters{1.0, 1.0, 1.0, 1.0});
    EXPECT_NEAR(r.hyperparameters.lengthScale, 0.4, 0.08);
    EXPECT_NEAR(r.hyperparameters.sigmaF, 3.0, 0.9);
    EXPECT_NEAR(r.hyperparameters.sigmaN, 0.3, 0.06);
    EXPECT_GT(
        r.logMarginal,
        fitHyperparameters(stretches, GpHyperparameters{1.0, 1.0, 1.0, 1.0}).logMarginal - 1e-6);
}
