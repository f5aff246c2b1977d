// The simulated gyro: its rates integrate to the carrier's true rotation (hand-held or on the
// robot), its bias and noise are the spec's, and adding it leaves the other sensors' samples
// as they were.
#include <gtest/gtest.h>
#include <lodestone/sim/SimGyro.h>
#include <lodestone/sim/SimulatorSource.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationIMU.h>

#include "SimTestWorlds.h"

using namespace lodestone::sim;

namespace {
MotionPlan planOf(const Scenario& sc) {
    return MotionPlan(sc.motion, {}, [](const Eigen::Vector2d&, const Eigen::Vector2d&) { return true; });
}

/** The gyro's samples integrated (body frame, rate held over each period) from t0 to t1. */
Eigen::Matrix3d integrate(SimGyro& gyro, double t0, double t1) {
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    while (gyro.nextTimeNs() < static_cast<std::int64_t>(t1 * 1e9)) {
        const double t = gyro.nextTimeNs() * 1e-9;
        const auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservationIMU>(gyro.produce());
        if (t < t0) continue;
        const Eigen::Vector3d w(obs->get(mrpt::obs::IMU_WX), obs->get(mrpt::obs::IMU_WY),
                                obs->get(mrpt::obs::IMU_WZ));
        const double dt = 0.01;  // 100 Hz
        if (w.norm() > 0) R = R * Eigen::AngleAxisd(w.norm() * dt, w.normalized()).toRotationMatrix();
    }
    return R;
}

double angleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
    return Eigen::AngleAxisd(a.transpose() * b).angle();
}
}  // namespace

TEST(SimGyro, HandHeldRatesIntegrateToTheCamerasRotation) {
    Scenario sc = lodestone::test::boxScenario();
    sc.motion.waypoints = {{0, 0}, {4, 0}, {4, 2}, {0, 2}};
    const MotionPlan plan = planOf(sc);
    const HandheldMotion hand(plan, HandheldSpec{}, Random(4));
    GyroSpec spec;
    spec.biasSigma = 0;
    spec.noiseStd = 0;
    SimGyro exact(plan, &hand, spec, 0, Random(9));
    const double t1 = std::min(20.0, plan.duration());
    const Eigen::Matrix3d truth = hand.poseAt(0).linear().transpose() * hand.poseAt(t1).linear();
    EXPECT_GT(Eigen::AngleAxisd(truth).angle(), 0.5) << "the path turns";
    EXPECT_LT(angleBetween(integrate(exact, 0, t1), truth), 0.2 * M_PI / 180);

    // With the spec's MEMS bias the same integration drifts by about |bias| t.
    GyroSpec mems;
    SimGyro biased(plan, &hand, mems, 0, Random(9));
    const double drift = biased.bias().norm() * t1;
    EXPECT_GT(biased.bias().norm(), 0);
    EXPECT_NEAR(angleBetween(integrate(biased, 0, t1), truth), drift, 0.3 * drift + 0.01);
}

TEST(SimGyro, OnTheRobotItMeasuresTheYawRate) {
    Scenario sc = lodestone::test::boxScenario();
    sc.motion.waypoints = {{0, 0}, {4, 0}, {4, 2}};  // a closed loop: back to the start
    const MotionPlan plan = planOf(sc);
    GyroSpec spec;
    spec.biasSigma = 0;
    SimGyro gyro(plan, nullptr, spec, 0, Random(2));
    double yaw = 0, t = 0;
    while (gyro.nextTimeNs() != std::numeric_limits<std::int64_t>::max()) {
        t = gyro.nextTimeNs() * 1e-9;
        const auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservationIMU>(gyro.produce());
        EXPECT_EQ(obs->get(mrpt::obs::IMU_WX), obs->get(mrpt::obs::IMU_WX));  // present, not NaN
        EXPECT_LT(std::abs(obs->get(mrpt::obs::IMU_WX)), 5 * spec.noiseStd);  // level: noise only
        yaw += obs->get(mrpt::obs::IMU_WZ) * 0.01;
    }
    // Round the closed triangle: left turns adding up to most of a full turn, which the
    // plan's heading only shows modulo 2 pi.
    EXPECT_GT(yaw, M_PI);
    EXPECT_NEAR(std::remainder(yaw - (plan.poseAt(t).yaw - plan.poseAt(0).yaw), 2 * M_PI), 0, 0.02);
}

TEST(SimGyro, AddingItLeavesTheOtherSensorsAsTheyWere) {
    Scenario sc = lodestone::test::boxScenario();
    sc.camera.width = 32;
    sc.camera.height = 24;
    sc.camera.fx = sc.camera.fy = 28;
    sc.camera.cx = 15.5;
    sc.camera.cy = 11.5;
    Scenario withGyro = sc;
    withGyro.gyro = GyroSpec{};
    SimulatorSource a(sc, 7), b(withGyro, 7);
    std::vector<std::string> without, with;
    std::size_t imu = 0;
    for (int i = 0; i < 400; ++i) {
        auto o = a.next();
        ASSERT_TRUE(o);
        without.push_back(o->sensorLabel + " " + std::to_string(mrpt::Clock::toDouble(o->timestamp)));
    }
    while (with.size() < without.size()) {
        auto o = b.next();
        ASSERT_TRUE(o);
        if (auto g = std::dynamic_pointer_cast<mrpt::obs::CObservationIMU>(o)) {
            EXPECT_EQ(g->sensorLabel, "IMU");
            ++imu;
            continue;
        }
        with.push_back(o->sensorLabel + " " + std::to_string(mrpt::Clock::toDouble(o->timestamp)));
    }
    EXPECT_EQ(with, without);
    EXPECT_GT(imu, 100u);
}

TEST(SimGyro, ItsAccelerometerReadsGravitysReactionAndTheTurnsPull) {
    Scenario sc = lodestone::test::boxScenario();
    sc.motion.waypoints = {{0, 0}, {4, 0}, {4, 2}};
    const MotionPlan plan = planOf(sc);
    GyroSpec spec;
    spec.accelBiasSigma = 0;
    spec.accelNoiseStd = 0;
    SimGyro centre(plan, nullptr, spec, 0, Random(2));
    spec.pose.x = 0.2;  // 20 cm ahead of the wheels' axle
    SimGyro ahead(plan, nullptr, spec, 0, Random(2));
    // Driving straight at constant speed: 1 g up, nothing else.
    double straight = -1, turning = -1;
    for (double t = 0.5; t < plan.duration(); t += 0.05) {
        const Eigen::Vector2d v = plan.velocityAt(t), v1 = plan.velocityAt(t - 0.05),
                              v2 = plan.velocityAt(t + 0.05);
        if (straight < 0 && v.x() > 0.1 && std::abs(v.y()) < 1e-9 && v1 == v && v2 == v) straight = t;
        if (turning < 0 && std::abs(v.x()) < 1e-9 && std::abs(v.y()) > 0.1 && v1 == v && v2 == v)
            turning = t;
    }
    ASSERT_GT(straight, 0);
    ASSERT_GT(turning, 0) << "the path turns in place at its corner";
    EXPECT_LT((centre.trueSpecificForce(straight) - Eigen::Vector3d(0, 0, 9.81)).norm(), 1e-6);
    // Turning in place: the sensor on the axis feels nothing more, the one ahead of it is
    // pulled towards the axis by w^2 r.
    const double w = plan.velocityAt(turning).y();
    EXPECT_LT((centre.trueSpecificForce(turning) - Eigen::Vector3d(0, 0, 9.81)).norm(), 1e-6);
    const Eigen::Vector3d f = ahead.trueSpecificForce(turning);
    EXPECT_NEAR(f.x(), -w * w * 0.2, 1e-4);
    EXPECT_NEAR(f.z(), 9.81, 1e-6);
    // Its samples: the spec's noise about the truth plus a bias drawn once.
    spec.accelNoiseStd = 0.01;
    spec.accelBiasSigma = 0.02;
    SimGyro noisy(plan, nullptr, spec, 0, Random(5));
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int n = 0;
    while (noisy.nextTimeNs() < static_cast<std::int64_t>(straight * 1e9)) {
        const double t = noisy.nextTimeNs() * 1e-9;
        const auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservationIMU>(noisy.produce());
        ASSERT_TRUE(obs->has(mrpt::obs::IMU_X_ACC) && obs->has(mrpt::obs::IMU_Z_ACC));
        const Eigen::Vector3d a(obs->get(mrpt::obs::IMU_X_ACC), obs->get(mrpt::obs::IMU_Y_ACC),
                                obs->get(mrpt::obs::IMU_Z_ACC));
        sum += a - noisy.trueSpecificForce(t);
        ++n;
    }
    ASSERT_GT(n, 10);
    EXPECT_LT((sum / n - noisy.accelBias()).norm(), 4 * 0.01 / std::sqrt(double(n)) * std::sqrt(3.0));
    EXPECT_GT(noisy.accelBias().norm(), 0);
}
