// Up from an accelerometer: a tilted sensor at rest gives its tilt, a turn inside the window
// does not smear it (the gyro turns the samples into one frame), a known acceleration is taken
// out, an unknown steady one the window cannot tell from tilt, a jerky one widens the sigma, and
// the uncovered is refused.
#include <gtest/gtest.h>
#include <lodestone/odometry/GravityEstimator.h>

#include <random>

using namespace lodestone::odometry;

namespace {
mrpt::obs::CObservationIMU sample(double t, const Eigen::Vector3d& w, const Eigen::Vector3d& f) {
    mrpt::obs::CObservationIMU imu;
    imu.timestamp = mrpt::Clock::fromDouble(t);
    imu.sensorLabel = "IMU";
    imu.set(mrpt::obs::IMU_WX, w.x());
    imu.set(mrpt::obs::IMU_WY, w.y());
    imu.set(mrpt::obs::IMU_WZ, w.z());
    imu.set(mrpt::obs::IMU_X_ACC, f.x());
    imu.set(mrpt::obs::IMU_Y_ACC, f.y());
    imu.set(mrpt::obs::IMU_Z_ACC, f.z());
    return imu;
}

double angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::atan2(a.cross(b).norm(), a.dot(b));
}

const Eigen::Vector3d kUp(0, 0, 1);
}  // namespace

TEST(GravityEstimator, ATiltedSensorAtRestGivesItsTiltWithinItsSigma) {
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0, 0.01);
    GravityEstimator g;
    // The sensor pitched 5 deg and rolled -3 deg: the world's up in its frame.
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(5 * M_PI / 180, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(-3 * M_PI / 180, Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
    const Eigen::Vector3d up = R.transpose() * kUp;
    for (int k = 0; k <= 150; ++k) {
        const Eigen::Vector3d n(noise(rng), noise(rng), noise(rng));
        ASSERT_TRUE(g.add(sample(100 + 0.01 * k, Eigen::Vector3d::Zero(), 9.81 * up + n)));
    }
    const auto u = g.at(101.5);
    ASSERT_TRUE(u);
    EXPECT_LT(angle(u->up, up), 3 * u->sigma);
    EXPECT_LT(angle(u->up, up), 0.05 * M_PI / 180);
    // At rest the sigma is the bias left (2 mg: 0.12 deg) and little else.
    EXPECT_NEAR(u->sigma, 0.02 / 9.81, 0.0005);
    EXPECT_GE(u->samples, 95);
}

TEST(GravityEstimator, ATurnInsideTheWindowIsUndoneByTheGyro) {
    GravityEstimator g;
    // Rolling at 0.5 rad/s through the window: the up seen by the sensor turns by 29 deg; the
    // window's mean without the gyro would sit half-way.
    const double rate = 0.5;
    const auto bodyAt = [&](double s) {  // world <- sensor
        return Eigen::Matrix3d(Eigen::AngleAxisd(rate * s, Eigen::Vector3d::UnitX()));
    };
    for (int k = 0; k <= 100; ++k) {
        const double s = 0.01 * k;
        ASSERT_TRUE(
            g.add(sample(50 + s, Eigen::Vector3d(rate, 0, 0), 9.81 * bodyAt(s).transpose() * kUp)));
    }
    const auto u = g.at(51.0);
    ASSERT_TRUE(u);
    const Eigen::Vector3d truth = bodyAt(1.0).transpose() * kUp;
    // (the rate held over each 10 ms interval: the samples' own discretisation, 0.15 deg)
    EXPECT_LT(angle(u->up, truth), 0.3 * M_PI / 180);
    EXPECT_GT(angle(bodyAt(0.5).transpose() * kUp, truth), 10 * M_PI / 180);
}

TEST(GravityEstimator, AKnownAccelerationIsTakenOutAndAnUnknownOneIsNot) {
    GravityEstimator g;
    // Level, speeding up along x at 0.5 m/s^2 for the whole window.
    const Eigen::Vector3d a(0.5, 0, 0);
    for (int k = 0; k <= 100; ++k)
        ASSERT_TRUE(g.add(sample(10 + 0.01 * k, Eigen::Vector3d::Zero(), a + 9.81 * kUp)));
    const auto unknown = g.at(11.0);
    const auto known = g.at(11.0, a, 0.01);
    ASSERT_TRUE(unknown && known);
    // Steady acceleration and tilt look the same to an accelerometer: 2.9 deg off.
    EXPECT_GT(angle(unknown->up, kUp), 2.5 * M_PI / 180);
    EXPECT_LT(angle(known->up, kUp), 0.01 * M_PI / 180);
    EXPECT_GT(known->sigma, unknown->sigma) << "the acceleration's own uncertainty counts";
}

TEST(GravityEstimator, AJerkyCarrierWidensTheSigmaAndTheUncoveredIsRefused) {
    GravityEstimator g;
    // A hand's bob: 3 m/s^2 at 2 Hz up and down.
    for (int k = 0; k <= 100; ++k) {
        const double s = 0.01 * k;
        const Eigen::Vector3d f = (9.81 + 3 * std::sin(2 * M_PI * 2 * s)) * kUp;
        g.add(sample(20 + s, Eigen::Vector3d::Zero(), f));
    }
    const auto u = g.at(21.0);
    ASSERT_TRUE(u);
    EXPECT_GT(u->sigma, 5 * 0.02 / 9.81);
    EXPECT_FALSE(g.at(19.5)) << "before the first sample";
    EXPECT_FALSE(g.at(21.5)) << "0.5 s after the last";
    EXPECT_FALSE(g.at(20.2)) << "a window covered a fifth of the way";
    // Falling: nothing like 1 g.
    GravityEstimator falling;
    for (int k = 0; k <= 100; ++k)
        falling.add(sample(30 + 0.01 * k, Eigen::Vector3d::Zero(), 0.5 * kUp));
    EXPECT_FALSE(falling.at(31.0));
    // A sample without accelerations is no sample here.
    mrpt::obs::CObservationIMU gyroOnly;
    gyroOnly.timestamp = mrpt::Clock::fromDouble(40);
    gyroOnly.set(mrpt::obs::IMU_WX, 0.0);
    gyroOnly.set(mrpt::obs::IMU_WY, 0.0);
    gyroOnly.set(mrpt::obs::IMU_WZ, 0.0);
    EXPECT_FALSE(falling.add(gyroOnly));
}
