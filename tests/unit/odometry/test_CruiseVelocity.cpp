// The carrier's cruise: VO's velocity averaged over the last seconds of tracking.
#include <gtest/gtest.h>
#include <lodestone/odometry/CruiseVelocity.h>

#include <cmath>
#include <Eigen/Core>

#include <limits>
#include <random>

using lodestone::odometry::CruiseVelocity;

// Driving at 0.3 m/s, the cruise is that pace from the first second on, each frame's VO error
// averaging out; a turn in place (no forward step) lowers it by the turn's share of the window,
// and driving on brings it back.
TEST(CruiseVelocity, ItIsTheCarriersPaceOverTheWindow) {
    CruiseVelocity cruise(10.0);
    EXPECT_EQ(cruise.mean().norm(), 0.0);
    const double dt = 1 / 30.0;
    std::mt19937_64 rng(3);
    std::normal_distribution<double> n(0, 0.005);  // [m] a frame's VO error, per axis
    Eigen::Vector3d error = Eigen::Vector3d::Zero();  // (each step: the difference of two frames')
    const auto drive = [&](double seconds, double speed) {
        for (int k = 0; k < std::lround(seconds / dt); ++k) {
            const Eigen::Vector3d next(n(rng), n(rng), n(rng));
            cruise.add(Eigen::Vector3d(speed * dt, 0, 0) + next - error, dt);
            error = next;
        }
    };
    drive(1, 0.3);
    EXPECT_NEAR(cruise.mean().x(), 0.3, 0.01);
    drive(49, 0.3);
    EXPECT_NEAR(cruise.mean().x(), 0.3, 0.01);
    EXPECT_LT(cruise.mean().tail<2>().norm(), 0.01);
    drive(2.6, 0.0);  // a quarter turn in place at 35 deg/s
    // (the 50 s before weigh 10 (1 - e^-5) e^-0.26 s of the 10 (1 - e^-5.26) s the window holds)
    EXPECT_NEAR(cruise.mean().x(), 0.3 * std::exp(-0.26) * -std::expm1(-5.0) / -std::expm1(-5.26), 0.005);
    drive(30, 0.3);
    EXPECT_NEAR(cruise.mean().x(), 0.3, 0.01);
}

// Steps of no time or not finite are left out; with no window there is no cruise.
TEST(CruiseVelocity, BadStepsAndNoWindowLeaveItAlone) {
    CruiseVelocity cruise(10.0);
    cruise.add(Eigen::Vector3d(0.01, 0, 0), 1 / 30.0);
    const Eigen::Vector3d before = cruise.mean();
    cruise.add(Eigen::Vector3d(0.01, 0, 0), 0.0);
    cruise.add(Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 0, 0), 1 / 30.0);
    cruise.add(Eigen::Vector3d(0.01, 0, 0), -1.0);
    EXPECT_EQ(cruise.mean(), before);
    CruiseVelocity none;
    none.add(Eigen::Vector3d(0.01, 0, 0), 1 / 30.0);
    EXPECT_EQ(none.mean().norm(), 0.0);
}
