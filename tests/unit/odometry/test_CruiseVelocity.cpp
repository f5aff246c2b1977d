// The carrier's cruise: VO's velocity over the last seconds of tracking, against its turn rate.
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
    EXPECT_EQ(cruise.at(0).norm(), 0.0);
    const double dt = 1 / 30.0;
    std::mt19937_64 rng(3);
    std::normal_distribution<double> n(0, 0.005);  // [m] a frame's VO error, per axis
    Eigen::Vector3d error = Eigen::Vector3d::Zero();  // (each step: the difference of two frames')
    const auto drive = [&](double seconds, double speed) {
        for (int k = 0; k < std::lround(seconds / dt); ++k) {
            const Eigen::Vector3d next(n(rng), n(rng), n(rng));
            cruise.add(Eigen::Vector3d(speed * dt, 0, 0) + next - error, dt, 0.0);
            error = next;
        }
    };
    drive(1, 0.3);
    EXPECT_NEAR(cruise.at(0).x(), 0.3, 0.01);
    drive(49, 0.3);
    EXPECT_NEAR(cruise.at(0).x(), 0.3, 0.01);
    EXPECT_LT(cruise.at(0).tail<2>().norm(), 0.01);
    drive(2.6, 0.0);  // a quarter turn in place at 35 deg/s
    // (the 50 s before weigh 10 (1 - e^-5) e^-0.26 s of the 10 (1 - e^-5.26) s the window holds)
    EXPECT_NEAR(cruise.at(0).x(), 0.3 * std::exp(-0.26) * -std::expm1(-5.0) / -std::expm1(-5.26), 0.005);
    drive(30, 0.3);
    EXPECT_NEAR(cruise.at(0).x(), 0.3, 0.01);
}

// Steps of no time or not finite are left out; with no window there is no cruise.
TEST(CruiseVelocity, BadStepsAndNoWindowLeaveItAlone) {
    CruiseVelocity cruise(10.0);
    cruise.add(Eigen::Vector3d(0.01, 0, 0), 1 / 30.0, 0.0);
    const Eigen::Vector3d before = cruise.at(0);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    cruise.add(Eigen::Vector3d(0.01, 0, 0), 0.0, 0.0);
    cruise.add(Eigen::Vector3d(nan, 0, 0), 1 / 30.0, 0.0);
    cruise.add(Eigen::Vector3d(0.01, 0, 0), 1 / 30.0, nan);
    cruise.add(Eigen::Vector3d(0.01, 0, 0), -1.0, 0.0);
    EXPECT_EQ(cruise.at(0), before);
    EXPECT_EQ(cruise.at(nan).norm(), 0.0);
    CruiseVelocity none;
    none.add(Eigen::Vector3d(0.01, 0, 0), 1 / 30.0, 0.0);
    EXPECT_EQ(none.at(0).norm(), 0.0);
}

// A robot stops at each waypoint and turns on the spot. After a straight corridor its window
// holds no turn: turning at 35 deg/s, nothing is known of its pace there, and the cruise is rest
// (not 0.3 m/s along a turning heading). Once a turn on the spot is in the window, its pace
// while turning is the regression's: still about rest - and straight on, the corridor's pace.
TEST(CruiseVelocity, ACarrierTurningOnTheSpotDoesNotCruise) {
    CruiseVelocity cruise(10.0);
    const double dt = 1 / 30.0, turn = 35 * M_PI / 180;
    std::mt19937_64 rng(5);
    std::normal_distribution<double> rateError(0, 2 * M_PI / 180);  // [rad/s] VO's turn rate
    const auto drive = [&](double seconds, double speed, double rate) {
        for (int k = 0; k < std::lround(seconds / dt); ++k)
            cruise.add(Eigen::Vector3d(speed * dt, 0, 0), dt, std::abs(rate + rateError(rng)));
    };
    drive(30, 0.3, 0.0);
    EXPECT_NEAR(cruise.at(0).x(), 0.3, 0.01);
    EXPECT_NEAR(cruise.at(3 * M_PI / 180).x(), 0.3, 0.03) << "a straight corridor's wobble";
    EXPECT_EQ(cruise.at(turn).norm(), 0.0) << cruise.at(turn).transpose();
    drive(2.6, 0.0, turn);
    drive(5, 0.3, 0.0);
    EXPECT_LT(std::abs(cruise.at(turn).x()), 0.03) << "the turn on the spot in the window";
    EXPECT_NEAR(cruise.at(0).x(), 0.3, 0.03);
}
