// squaredMahalanobis: the gate VisualOdometryNRD puts between a gap's motion model and a view
// found again after it.
#include <gtest/gtest.h>
#include <lodestone/graphslam/Se3Pose.h>

#include <cmath>

using lodestone::graphslam::squaredMahalanobis;
using mrpt::poses::CPose3D;
using mrpt::poses::CPose3DPDFGaussian;

namespace {
CPose3DPDFGaussian gaussian(const CPose3D& mean, double sigmaXyz, double sigmaAngle) {
    CPose3DPDFGaussian p;
    p.mean = mean;
    p.cov.setZero();
    for (int k = 0; k < 3; ++k) {
        p.cov(k, k) = sigmaXyz * sigmaXyz;
        p.cov(k + 3, k + 3) = sigmaAngle * sigmaAngle;
    }
    return p;
}
}  // namespace

TEST(Se3Pose, SquaredMahalanobisSumsBothCovariances) {
    const auto a = gaussian(CPose3D(1, 2, 0, 0.3, 0, 0), 0.1, 0.01);
    EXPECT_NEAR(squaredMahalanobis(a, a), 0.0, 1e-12);
    // 0.2 m apart in x, each 0.1 m: (0.2)^2 / (2 * 0.1^2) = 2
    const auto b = gaussian(CPose3D(1.2, 2, 0, 0.3, 0, 0), 0.1, 0.01);
    EXPECT_NEAR(squaredMahalanobis(a, b), 2.0, 1e-9);
    EXPECT_NEAR(squaredMahalanobis(b, a), 2.0, 1e-9);
    // A certain pose against a loose one: the loose one's covariance alone.
    const auto certain = gaussian(CPose3D(1, 2, 0, 0.3, 0, 0), 0, 0);
    EXPECT_NEAR(squaredMahalanobis(certain, b), 4.0, 1e-6);
}

TEST(Se3Pose, SquaredMahalanobisWrapsTheAngles) {
    // Headings of +179 and -179 deg are 2 deg apart, not 358.
    const double deg = M_PI / 180;
    const auto a = gaussian(CPose3D(0, 0, 0, 179 * deg, 0, 0), 0.1, 1 * deg);
    const auto b = gaussian(CPose3D(0, 0, 0, -179 * deg, 0, 0), 0.1, 1 * deg);
    EXPECT_NEAR(squaredMahalanobis(a, b), 2.0, 1e-6);  // (2 deg)^2 / (2 * (1 deg)^2)
    // A view aligned at a half turn about a vertical edge 3.9 m ahead (what the gate is for:
    // 171 deg and 7.8 m from where the gyro's bridge put it) is far beyond chi-square 99.9 %.
    const auto bridge = gaussian(CPose3D(0.07, 0, 0, 0, 0, 0), 0.05, 0.5 * deg);
    const auto aliased = gaussian(CPose3D(7.4, -2.56, 0, 171 * deg, 0, 0), 0.12, 0.3 * deg);
    EXPECT_GT(squaredMahalanobis(bridge, aliased), 22.458);
}
