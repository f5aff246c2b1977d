#include <gtest/gtest.h>
#include <lodestone/sim/MotionPlan.h>

#include <cmath>

using namespace lodestone::sim;

namespace {
MotionPlan::Params square() {
    MotionPlan::Params p;
    p.waypoints = {{0, 0}, {4, 0}, {4, 3}, {0, 3}};
    p.laps = 2;
    p.speed = 0.5;
    p.turnRate = M_PI / 4;  // 90 degrees in 2 s
    return p;
}
const auto anywhere = [](const Eigen::Vector2d&, const Eigen::Vector2d&) { return true; };
}  // namespace

TEST(MotionPlan, LapsOfTheLoopWithClosedFormTiming) {
    const MotionPlan plan(square(), {}, anywhere);
    // Per lap: 14 m at 0.5 m/s = 28 s, plus turns; 2 laps, then a 1 s stop.
    // Turns: before legs 2, 3, 4 of lap 1 and all 4 of lap 2 = 7 turns of 90 degrees, 2 s each.
    EXPECT_NEAR(plan.duration(), 2 * 28 + 7 * 2 + 1, 1e-9);
    const RobotPose start = plan.poseAt(0);
    EXPECT_NEAR(start.x, 0, 1e-12);
    EXPECT_NEAR(start.yaw, 0, 1e-12);
    const RobotPose mid = plan.poseAt(4.0);  // 2 m along the first leg
    EXPECT_NEAR(mid.x, 2.0, 1e-12);
    EXPECT_NEAR(mid.y, 0.0, 1e-12);
    const RobotPose turning = plan.poseAt(9.0);  // half-way through the first turn
    EXPECT_NEAR(turning.x, 4.0, 1e-12);
    EXPECT_NEAR(turning.yaw, M_PI / 4, 1e-12);
    EXPECT_FALSE(plan.liftedAt(9.0));
}

TEST(MotionPlan, WheelAnglesIntegrateToThePose) {
    const MotionPlan plan(square(), {}, anywhere);
    const auto& p = plan.params();
    double x = 0, y = 0, yaw = 0;
    Eigen::Vector2d prev = plan.wheelAnglesAt(0);
    const double dt = 0.01;
    for (double t = dt; t <= plan.duration(); t += dt) {
        const Eigen::Vector2d w = plan.wheelAnglesAt(t);
        const double dl = (w[0] - prev[0]) * p.wheelRadius, dr = (w[1] - prev[1]) * p.wheelRadius;
        prev = w;
        const double ds = 0.5 * (dl + dr), dyaw = (dr - dl) / p.wheelBase;
        x += ds * std::cos(yaw + dyaw / 2);
        y += ds * std::sin(yaw + dyaw / 2);
        yaw += dyaw;
        if (std::fmod(t, 5.0) < dt) {
            const RobotPose truth = plan.poseAt(t);
            ASSERT_NEAR(x, truth.x, 1e-6) << "t = " << t;
            ASSERT_NEAR(y, truth.y, 1e-6) << "t = " << t;
            ASSERT_NEAR(std::remainder(yaw - truth.yaw, 2 * M_PI), 0, 1e-6) << "t = " << t;
        }
    }
}

TEST(MotionPlan, KidnapCarriesThenResumesAtTheNearestWaypoint) {
    KidnapSpec k;
    k.name = "kidnap_1";
    k.start = 5.0;
    k.duration = 6.0;
    k.putDown = {3.5, 3.2, M_PI, 0};
    const MotionPlan plan(square(), {k}, anywhere);
    EXPECT_FALSE(plan.liftedAt(4.9));
    EXPECT_TRUE(plan.liftedAt(5.1));
    EXPECT_TRUE(plan.liftedAt(10.9));
    EXPECT_FALSE(plan.liftedAt(11.1));
    EXPECT_GT(plan.poseAt(8.0).z, 0.1);  // off the ground half-way
    const RobotPose down = plan.poseAt(11.0);
    EXPECT_NEAR(down.x, 3.5, 1e-9);
    EXPECT_NEAR(down.y, 3.2, 1e-9);
    EXPECT_NEAR(down.z, 0.0, 1e-9);
    // Wheels do not turn while carried.
    EXPECT_EQ(plan.wheelAnglesAt(5.0), plan.wheelAnglesAt(11.0));
    // The nearest waypoint to (3.5, 3.2) is (4, 3): the robot drives there next.
    bool reached = false;
    for (double t = 11; t < plan.duration(); t += 0.05) {
        const RobotPose p = plan.poseAt(t);
        if (std::hypot(p.x - 4, p.y - 3) < 1e-6) {
            reached = true;
            break;
        }
    }
    EXPECT_TRUE(reached);
}

TEST(MotionPlan, ADriveCutByAKidnapAfterALapKeepsItsHeading) {
    // Lap 1 ends at 34 s facing south after three left turns (heading 3 pi / 2, unwrapped);
    // the turn to east ends at 36 s and lap 2's first drive is cut by a lift at 40 s.
    KidnapSpec k;
    k.name = "kidnap_1";
    k.start = 40.0;
    k.duration = 4.0;
    k.putDown = {2.0, 3.0, M_PI, 0};
    const MotionPlan plan(square(), {k}, anywhere);
    for (double t = 36.1; t < 40.0; t += 0.3) {
        const RobotPose p = plan.poseAt(t);
        EXPECT_NEAR(std::remainder(p.yaw, 2 * M_PI), 0, 1e-9) << "t = " << t;  // driving east
        EXPECT_NEAR(p.x, 0.5 * (t - 36), 1e-9) << "t = " << t;
    }
}

TEST(MotionPlan, PutDownWithNoReachableWaypointIsNamed) {
    KidnapSpec k;
    k.name = "scenario.ini [kidnap] key 'kidnap_3'";
    k.start = 1.0;
    k.duration = 1.0;
    k.putDown = {10, 10, 0, 0};
    const auto nowhere = [](const Eigen::Vector2d&, const Eigen::Vector2d&) { return false; };
    try {
        MotionPlan plan(square(), {k}, nowhere);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("kidnap_3"), std::string::npos) << e.what();
    }
}
