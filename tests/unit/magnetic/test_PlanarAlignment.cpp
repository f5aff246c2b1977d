// The 2-D GP and the planar GP alignment: the mean's gradient against numerical
// differentiation, a query stretch that passed beside two earlier passes moved back onto its
// true positions, and a stretch from a different field found not to fit.
#include <gtest/gtest.h>
#include <lodestone/magnetic/PlanarAlignment.h>

#include "PlaneField.h"

#include <cmath>
#include <random>

using namespace lodestone::magnetic;

using namespace lodestone::test;

namespace {
GaussianProcess2D targetGp(const PlaneField& field) {
    std::vector<Eigen::Vector2d> at;
    std::vector<Eigen::VectorXd> values;
    pass(field, 0.0, 0, 4, at, values);   // two earlier passes, 0.3 m apart
    pass(field, 0.3, 0, 4, at, values);
    GaussianProcess2D gp({4.0, 0.35, 0.2, 10.0});
    gp.fit(rowsOf(at), rowsOf(values));
    return gp;
}
}  // namespace

TEST(GaussianProcess2D, MeanGradientMatchesNumericalDerivative) {
    const PlaneField field(3);
    const auto gp = targetGp(field);
    const Eigen::Vector2d p(1.7, 0.12);
    Eigen::MatrixX2d grad;
    gp.mean(p, &grad);
    const double h = 1e-6;
    for (int k = 0; k < 2; ++k) {
        const Eigen::Vector2d d = Eigen::Vector2d::Unit(k) * h;
        const Eigen::VectorXd num = (gp.mean(p + d) - gp.mean(p - d)) / (2 * h);
        for (int c = 0; c < 2; ++c) EXPECT_NEAR(grad(c, k), num[c], 1e-5 * (1 + std::abs(num[c])));
    }
    // The variance is small on the passes and back to the prior far from them.
    EXPECT_LT(gp.variance({2.0, 0.0}), 0.1);
    // (the constant term is learnt from the data, so what is left far away is mostly sigma_f^2)
    const double far = gp.variance({2.0, 5.0});
    EXPECT_GT(far, 4.0 * 4.0 + 0.2 * 0.2);
    EXPECT_LT(far, 4.0 * 4.0 + 0.2 * 0.2 + 4.0);
}

TEST(PlanarAlignment, MovesAStretchThatPassedBesideBackOntoItsTruePositions) {
    for (unsigned seed : {3u, 4u, 5u}) {
        const PlaneField field(seed);
        const auto gp = targetGp(field);
        // The revisit truly went along y = 0.15, x in [1, 3]; the odometry puts it 0.12 m back
        // along the path, 0.1 m to the side and turned by 3 degrees.
        std::vector<Eigen::Vector2d> truth;
        std::vector<Eigen::VectorXd> values;
        pass(field, 0.15, 1, 3, truth, values);
        const double a = 3 * M_PI / 180;
        Eigen::Matrix2d R;
        R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
        std::vector<Eigen::Vector2d> start;
        for (const auto& p : truth) start.push_back(R * (p - Eigen::Vector2d(2, 0.15)) + Eigen::Vector2d(2 - 0.12, 0.05));
        const auto r = alignInPlane(gp, rowsOf(start), rowsOf(values), {});
        ASSERT_TRUE(r.valid) << "seed " << seed;
        double worst = 0, worstStart = 0;
        for (std::size_t i = 0; i < truth.size(); ++i) {
            worst = std::max(worst, (r.apply(start[i]) - truth[i]).norm());
            worstStart = std::max(worstStart, (start[i] - truth[i]).norm());
        }
        EXPECT_GT(worstStart, 0.15);
        EXPECT_LT(worst, 0.06) << "seed " << seed << " delta " << r.delta.transpose();
        // ... and the move it should have made lies within 3 of its reported sigmas.
        const Eigen::Vector2d centre = r.pivot - Eigen::Vector2d(2 - 0.12, 0.05);
        const Eigen::Vector2d trueMove = R.transpose() * centre - centre + Eigen::Vector2d(0.12, 0.10);
        for (int k = 0; k < 2; ++k)
            EXPECT_LT(std::abs(r.delta[k] - trueMove[k]), 3 * std::sqrt(r.covariance(k, k)))
                << "seed " << seed << " axis " << k;
        EXPECT_LT(r.normalizedRms, 2.0) << "seed " << seed;
        EXPECT_LT(r.normalizedRms, r.normalizedRmsStart);
        EXPECT_LT(std::sqrt(r.covariance(1, 1)), 0.1);
    }
}

TEST(PlanarAlignment, AStretchOfAnotherFieldDoesNotFit) {
    const PlaneField field(3), other(99);
    const auto gp = targetGp(field);
    std::vector<Eigen::Vector2d> at;
    std::vector<Eigen::VectorXd> values;
    pass(other, 0.15, 1, 3, at, values);
    const auto r = alignInPlane(gp, rowsOf(at), rowsOf(values), {});
    EXPECT_TRUE(!r.valid || r.normalizedRms > 2.0) << r.normalizedRms;
}
