#include <gtest/gtest.h>
#include <lodestone/vision/RigidRansac.h>

#include <Eigen/Eigenvalues>
#include <random>

using namespace lodestone::vision;

namespace {
Eigen::Isometry3d knownMotion() {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.rotate(Eigen::AngleAxisd(0.2, Eigen::Vector3d(0.3, -1, 0.2).normalized()));
    T.translation() = Eigen::Vector3d(0.12, -0.05, 0.3);
    return T;
}

// n points in front of a camera (z 1..4 m), mapped by T, with noise; `outliers` of them moved
// to random places.
void makePairs(int n, int outliers, double noise, Eigen::Matrix3Xd& src, Eigen::Matrix3Xd& dst) {
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u(-1.5, 1.5), z(1.0, 4.0);
    std::normal_distribution<double> g(0, noise);
    src.resize(3, n);
    dst.resize(3, n);
    const auto T = knownMotion();
    for (int i = 0; i < n; ++i) {
        src.col(i) = Eigen::Vector3d(u(rng), u(rng), z(rng));
        dst.col(i) = T * src.col(i) + Eigen::Vector3d(g(rng), g(rng), g(rng));
        if (i < outliers) dst.col(i) = Eigen::Vector3d(u(rng), u(rng), z(rng));
    }
}
}  // namespace

TEST(RigidRansac, SvdAlignmentIsExactWithoutNoise) {
    Eigen::Matrix3Xd src, dst;
    makePairs(10, 0, 0.0, src, dst);
    const Eigen::Isometry3d T = alignRigid(src, dst);
    EXPECT_LT((T.matrix() - knownMotion().matrix()).norm(), 1e-9);
    EXPECT_NEAR(T.rotation().determinant(), 1.0, 1e-12);  // a rotation, never a reflection
}

TEST(RigidRansac, RecoversAKnownTransformWithHalfTheMatchesWrong) {
    Eigen::Matrix3Xd src, dst;
    makePairs(200, 100, 0.003, src, dst);
    const RigidRansac ransac;
    const auto est = ransac.estimate(src, dst, 7);
    ASSERT_TRUE(est.success);
    const Eigen::Isometry3d err = knownMotion().inverse() * est.transform;
    EXPECT_LT(err.translation().norm(), 0.005);
    EXPECT_LT(Eigen::AngleAxisd(err.rotation()).angle(), 0.2 * M_PI / 180);
    EXPECT_NEAR(static_cast<double>(est.inliers.size()), 100, 3);
    for (int i : est.inliers) EXPECT_GE(i, 97) << "an outlier was taken as an inlier";
    EXPECT_LT(est.rmse, 0.01);
    // The covariance is a covariance, and about the right size.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(est.covariance);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
    EXPECT_LT(std::sqrt(est.covariance(3, 3)), 0.005);
}

TEST(RigidRansac, DeterministicForASeed) {
    Eigen::Matrix3Xd src, dst;
    makePairs(100, 50, 0.003, src, dst);
    const RigidRansac ransac;
    const auto a = ransac.estimate(src, dst, 3), b = ransac.estimate(src, dst, 3);
    EXPECT_EQ(a.inliers, b.inliers);
    EXPECT_EQ(a.transform.matrix(), b.transform.matrix());
}

TEST(RigidRansac, PureNoiseGivesNoEstimate) {
    Eigen::Matrix3Xd src, dst;
    makePairs(100, 100, 0.0, src, dst);  // every pair wrong
    const RigidRansac ransac;
    EXPECT_FALSE(ransac.estimate(src, dst, 1).success);
    EXPECT_FALSE(ransac.estimate(src.leftCols(2), dst.leftCols(2), 1).success);  // too few
}

TEST(RigidRansac, WeightingByDepthNoiseBeatsPlainLeastSquares) {
    // Noise growing with depth^2, as structured light has it: far points are much worse.
    double plainErr = 0, weightedErr = 0;
    for (unsigned seed = 1; seed <= 20; ++seed) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(-1.5, 1.5), z(0.8, 5.0);
        std::normal_distribution<double> g(0, 1);
        const int n = 150;
        Eigen::Matrix3Xd src(3, n), dst(3, n);
        Eigen::VectorXd w(n);
        const auto T = knownMotion();
        for (int i = 0; i < n; ++i) {
            src.col(i) = Eigen::Vector3d(u(rng), u(rng), z(rng));
            dst.col(i) = T * src.col(i);
            const double sigma = 0.002 + 1.425e-3 * dst(2, i) * dst(2, i);
            dst.col(i) += sigma * Eigen::Vector3d(g(rng), g(rng), g(rng));
            w[i] = 1.0 / (sigma * sigma);
        }
        plainErr += (knownMotion().inverse() * alignRigid(src, dst)).translation().norm();
        weightedErr +=
            (knownMotion().inverse() * alignRigidWeighted(src, dst, w)).translation().norm();
    }
    EXPECT_LT(weightedErr, 0.8 * plainErr);
    // Equal weights are plain least squares.
    Eigen::Matrix3Xd src, dst;
    makePairs(20, 0, 0.01, src, dst);
    const auto a = alignRigid(src, dst);
    const auto b = alignRigidWeighted(src, dst, Eigen::VectorXd::Constant(20, 3.0));
    EXPECT_LT((a.matrix() - b.matrix()).norm(), 1e-9);
}
