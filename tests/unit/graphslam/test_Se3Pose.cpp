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

// A step whose rise nothing measured (VO's features along one line: 1.7 m loose) is held to the
// carrier's height bound, and what correlates with the rise moves with it; a step that measured
// its rise to a millimetre keeps it.
TEST(Se3Pose, HeightHeldBoundsOnlyARiseNothingMeasured) {
    mrpt::poses::CPose3DPDFGaussian loose;
    loose.mean = mrpt::poses::CPose3D(0.10, 0.00, 0.80, 0.05, 0.0, 0.0);
    loose.cov.setZero();
    for (int k = 0; k < 6; ++k) loose.cov(k, k) = 1e-6;
    loose.cov(2, 2) = 1.7 * 1.7;
    loose.cov(0, 2) = loose.cov(2, 0) = 0.5 * 1.7 * 1e-3;  // (x correlated with the rise)
    const auto held = lodestone::graphslam::heightHeld(loose, 0.1);
    EXPECT_LT(std::abs(held.mean.z()), 0.01);
    EXPECT_NEAR(std::sqrt(held.cov(2, 2)), 0.1, 0.001);
    EXPECT_LT(held.mean.x(), loose.mean.x()) << "x moves with the rise it correlates with";
    EXPECT_NEAR(held.mean.yaw(), 0.05, 1e-12);
    EXPECT_NEAR(held.cov(1, 1), 1e-6, 1e-15);

    mrpt::poses::CPose3DPDFGaussian sure = loose;
    sure.mean = mrpt::poses::CPose3D(0.10, 0.00, 0.05, 0.05, 0.0, 0.0);
    sure.cov(2, 2) = 1e-6;
    sure.cov(0, 2) = sure.cov(2, 0) = 0;
    const auto kept = lodestone::graphslam::heightHeld(sure, 0.1);
    EXPECT_NEAR(kept.mean.z(), 0.05, 0.05 * 1e-3);
    EXPECT_NEAR(kept.cov(2, 2), 1e-6, 1e-9);
    const auto same = lodestone::graphslam::heightHeld(loose, 0);
    EXPECT_EQ(same.mean, loose.mean);

    // A rise correlated with a turn (VO's cross terms): held with them the turn moves too;
    // without, only the translation does and the rotation keeps its mean and covariance.
    mrpt::poses::CPose3DPDFGaussian turning = loose;
    turning.cov(3, 2) = turning.cov(2, 3) = 0.5 * 1.7 * 1e-3;  // (yaw with the rise)
    const auto both = lodestone::graphslam::heightHeld(turning, 0.1);
    EXPECT_LT(both.mean.yaw(), 0.05 - 1e-4);
    const auto translationOnly = lodestone::graphslam::heightHeld(turning, 0.1, false);
    EXPECT_NEAR(translationOnly.mean.yaw(), 0.05, 1e-12);
    EXPECT_NEAR(translationOnly.cov(3, 3), turning.cov(3, 3), 1e-15);
    EXPECT_EQ(translationOnly.cov(3, 2), 0.0);
    EXPECT_LT(std::abs(translationOnly.mean.z()), 0.01);
}

TEST(Se3Pose, TranslationHeldFillsOnlyTheDirectionsNotMeasured) {
    // VO's step at a plain wall: the distance to it (x) and the height measured to a
    // millimetre, sideways (y) not at all (1 m); the motion model: 0.1 m ahead, 0.05 m sure.
    mrpt::poses::CPose3DPDFGaussian step;
    step.mean = mrpt::poses::CPose3D(0.10, 0.30, 0.0, 0.02, 0.0, 0.0);
    step.cov.setZero();
    step.cov(0, 0) = step.cov(2, 2) = 1e-6;
    step.cov(1, 1) = 1.0;
    for (int k = 3; k < 6; ++k) step.cov(k, k) = 1e-6;
    step.cov(1, 3) = step.cov(3, 1) = 0.5 * 1e-3;  // (sideways with the turn)
    const Eigen::Vector3d model(0.12, 0.0, 0.0);
    const Eigen::Matrix3d M = 0.05 * 0.05 * Eigen::Matrix3d::Identity();
    const auto held = lodestone::graphslam::translationHeld(step, model, M);
    EXPECT_NEAR(held.mean.y(), 0.30 * 0.0025 / 1.0025, 1e-6) << "sideways: the model's, nearly";
    EXPECT_NEAR(std::sqrt(held.cov(1, 1)), 0.05, 0.001);
    EXPECT_NEAR(held.mean.x(), 0.10, 1e-5) << "ahead: VO's, measured 50x better than the model";
    EXPECT_NEAR(held.cov(0, 0), 1e-6, 1e-9);
    EXPECT_LT(held.mean.yaw(), 0.02) << "the turn moves with the sideways shift it correlates with";
    const auto kept = lodestone::graphslam::translationHeld(step, model, M, false);
    EXPECT_NEAR(kept.mean.yaw(), 0.02, 1e-12);
    EXPECT_EQ(kept.cov(1, 3), 0.0);
    // A model far looser than every measured direction changes nothing that counts.
    mrpt::poses::CPose3DPDFGaussian sure = step;
    sure.cov(1, 1) = 1e-6;
    sure.cov(1, 3) = sure.cov(3, 1) = 0;
    const auto same = lodestone::graphslam::translationHeld(sure, model, M);
    EXPECT_NEAR(same.mean.y(), 0.30, 0.30 * 1e-3);
    EXPECT_NEAR(same.cov(1, 1), 1e-6, 1e-9);
}
