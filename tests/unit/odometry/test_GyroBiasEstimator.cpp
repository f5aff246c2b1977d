// The gyro's bias learnt from another sensor's rotations over the same intervals (VO's): it
// converges to the bias within its own sigma, and an outlier interval is skipped.
#include <gtest/gtest.h>
#include <lodestone/odometry/GyroBiasEstimator.h>

#include <random>

using lodestone::odometry::GyroBiasEstimator;

namespace {
Eigen::Matrix3d rotation(const Eigen::Vector3d& v) {
    return v.norm() > 0 ? Eigen::AngleAxisd(v.norm(), v / v.norm()).toRotationMatrix()
                        : Eigen::Matrix3d::Identity();
}
}  // namespace

TEST(GyroBiasEstimator, ConvergesToTheBiasWithinItsSigmaAndSkipsAnOutlier) {
    const double deg = M_PI / 180;
    const Eigen::Vector3d bias = Eigen::Vector3d(0.1, -0.05, 0.13) * deg;  // [rad/s]
    const double measuredSigma = 0.03 * deg, seconds = 0.3;                // VO's keyframe steps
    GyroBiasEstimator estimator(0.1 * deg);
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0.0, measuredSigma);
    std::uniform_real_distribution<double> turn(-0.2, 0.2);
    for (int k = 0; k < 500; ++k) {
        // Whatever the carrier turned, the gyro (its estimate taken out) turned that much more
        // by the bias left; the other sensor saw the turn with its noise.
        const Eigen::Matrix3d truth = rotation(Eigen::Vector3d(turn(rng), turn(rng), turn(rng)));
        const Eigen::Matrix3d gyro = truth * rotation((bias - estimator.bias()) * seconds);
        const Eigen::Matrix3d measured =
            truth * rotation(Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
        estimator.update(gyro, measured, measuredSigma, seconds);
    }
    EXPECT_GT(estimator.updates(), 490);
    EXPECT_LT(estimator.sigma(), 0.01 * deg);
    EXPECT_LT((estimator.bias() - bias).norm(), 4 * estimator.sigma());
    // A step the other sensor got 5 deg wrong is its outlier, not the gyro's bias.
    const Eigen::Vector3d before = estimator.bias();
    const Eigen::Matrix3d gyro = rotation((bias - estimator.bias()) * seconds);
    EXPECT_FALSE(
        estimator.update(gyro, rotation(Eigen::Vector3d(0, 0, 5 * deg)), measuredSigma, seconds));
    EXPECT_EQ(estimator.bias(), before);
    EXPECT_EQ(estimator.skipped(), 1);
}
