// The gyro's samples integrated between two instants: exact for known rates, a frame between two
// samples covered, gaps and the uncovered refused, bad samples skipped, the sigma growing.
#include <gtest/gtest.h>
#include <lodestone/odometry/GyroIntegrator.h>

using namespace lodestone::odometry;

namespace {
mrpt::obs::CObservationIMU sample(double t, const Eigen::Vector3d& w) {
    mrpt::obs::CObservationIMU imu;
    imu.timestamp = mrpt::Clock::fromDouble(t);
    imu.sensorLabel = "IMU";
    imu.set(mrpt::obs::IMU_WX, w.x());
    imu.set(mrpt::obs::IMU_WY, w.y());
    imu.set(mrpt::obs::IMU_WZ, w.z());
    return imu;
}
}  // namespace

TEST(GyroIntegrator, ConstantRatesGiveTheirRotation) {
    GyroIntegrator g;
    const Eigen::Vector3d w(0.1, -0.2, 0.5);
    for (int k = 0; k <= 100; ++k) ASSERT_TRUE(g.add(sample(1000 + 0.01 * k, w)));
    // From 0.25 s to 0.755 s: between samples at both ends.
    const auto r = g.between(1000.25, 1000.755);
    ASSERT_TRUE(r);
    const Eigen::Matrix3d truth = Eigen::AngleAxisd(w.norm() * 0.505, w.normalized()).toRotationMatrix();
    EXPECT_LT(Eigen::AngleAxisd(truth.transpose() * r->R).angle(), 1e-9);
    const auto shorter = g.between(1000.25, 1000.35);
    ASSERT_TRUE(shorter);
    EXPECT_GT(r->sigma, shorter->sigma) << "the bias grows with time";
    // A frame just after the last sample is covered (the rate held), one 0.2 s later is not.
    EXPECT_TRUE(g.between(1000.9, 1001.02));
    EXPECT_FALSE(g.between(1000.9, 1001.2));
    // Before the first sample: not covered.
    EXPECT_FALSE(g.between(999.9, 1000.5));
}

// A turn speeding up (a hand starting a corner: 0 to 60 deg/s in a second), sampled at 100 Hz:
// each sample the rate at its instant. Integrated between two frames that fall between
// samples, the rotation is the turn's, to the microradian - not half a sample behind it
// (0.22 deg short, were each sample held over the interval after it).
TEST(GyroIntegrator, ATurnSpeedingUpIsNotHalfASampleBehind) {
    GyroIntegrator g;
    const double accel = 60 * M_PI / 180;  // [rad/s^2] about z
    for (int k = 0; k <= 120; ++k)
        ASSERT_TRUE(g.add(sample(1000 + 0.01 * k, {0, 0, accel * 0.01 * k})));
    const double t0 = 0.253, t1 = 0.987;  // (from the first sample)
    const auto r = g.between(1000 + t0, 1000 + t1);
    ASSERT_TRUE(r);
    const double turned = 0.5 * accel * (t1 * t1 - t0 * t0);
    const Eigen::AngleAxisd got(r->R);
    EXPECT_NEAR(got.angle() * got.axis().z(), turned, 1e-6);
}

TEST(GyroIntegrator, AGapIsNotIntegratedOverAndBadSamplesAreSkipped) {
    GyroIntegrator g;
    const Eigen::Vector3d w(0, 0, 1);
    for (int k = 0; k < 10; ++k) g.add(sample(0.01 * k + 10, w));
    for (int k = 0; k < 10; ++k) g.add(sample(0.01 * k + 10.5, w));  // 0.41 s without samples
    EXPECT_TRUE(g.between(10.0, 10.08));
    EXPECT_FALSE(g.between(10.05, 10.55));
    EXPECT_FALSE(g.add(sample(10.52, w))) << "older than the last";
    EXPECT_FALSE(g.add(sample(11, Eigen::Vector3d(0, NAN, 0))));
    mrpt::obs::CObservationIMU noRates;
    noRates.timestamp = mrpt::Clock::fromDouble(12);
    EXPECT_FALSE(g.add(noRates));
    g.dropBefore(10.55);
    EXPECT_FALSE(g.between(10.5, 10.56)) << "dropped";
    EXPECT_TRUE(g.between(10.55, 10.58));
}

TEST(GyroIntegrator, ASetBiasIsTakenOutOfEverySample) {
    GyroIntegrator g;
    const Eigen::Vector3d w(0.0, 0.0, 0.3), bias(0.002, -0.001, 0.003);
    for (int k = 0; k <= 100; ++k) ASSERT_TRUE(g.add(sample(1000 + 0.01 * k, w + bias)));
    const auto raw = g.between(1000.0, 1001.0);
    g.setBias(bias, 0.0001);
    const auto corrected = g.between(1000.0, 1001.0);
    ASSERT_TRUE(raw && corrected);
    const Eigen::Matrix3d truth = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    EXPECT_GT(Eigen::AngleAxisd(truth.transpose() * raw->R).angle(), 0.003);
    EXPECT_LT(Eigen::AngleAxisd(truth.transpose() * corrected->R).angle(), 1e-9);
    EXPECT_LT(corrected->sigma, raw->sigma) << "the bias known better: a smaller sigma";
}
