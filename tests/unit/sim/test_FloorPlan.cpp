#include <gtest/gtest.h>
#include <lodestone/sim/FloorPlan.h>

using namespace lodestone::sim;

TEST(FloorPlan, RayHitsTheNearestWallWithPositionAndIncidence) {
    FloorPlan plan;
    plan.addWall({{3, -5}, {3, 5}, 2.6, 0});
    plan.addWall({{6, -5}, {6, 5}, 2.6, 1});
    const auto hit = plan.castRay({0, 0}, {1, 0}, 1e-9, 100);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->wall, 0);
    EXPECT_NEAR(hit->t, 3.0, 1e-12);
    EXPECT_NEAR(hit->u, 5.0, 1e-12);  // from the wall's end a = (3, -5)
    EXPECT_NEAR(hit->cosIncidence, 1.0, 1e-12);
    const auto oblique = plan.castRay({0, 0}, {1, 1}, 1e-9, 100);  // 45 degrees
    ASSERT_TRUE(oblique);
    EXPECT_NEAR(oblique->t, 3.0, 1e-12);
    EXPECT_NEAR(oblique->u, 8.0, 1e-12);
    EXPECT_NEAR(oblique->cosIncidence, std::sqrt(0.5), 1e-12);
    EXPECT_FALSE(plan.castRay({0, 0}, {-1, 0}, 1e-9, 100));
    EXPECT_FALSE(plan.castRay({0, 0}, {1, 0}, 1e-9, 2.0));  // beyond tMax
}

TEST(FloorPlan, ClearanceAndBlockedMoves) {
    FloorPlan plan;
    plan.addWall({{0, 0}, {10, 0}, 2.6, 0});
    EXPECT_NEAR(plan.clearance({5, 1.5}), 1.5, 1e-12);
    EXPECT_NEAR(plan.clearance({-3, 4}), 5.0, 1e-12);      // to the end point
    EXPECT_TRUE(plan.blocks({5, 1}, {5, -1}, 0.1));        // through the wall
    EXPECT_TRUE(plan.blocks({0, 0.15}, {10, 0.15}, 0.2));  // too close along it
    EXPECT_FALSE(plan.blocks({0, 0.5}, {10, 0.5}, 0.2));
    EXPECT_EQ(plan.minCorner(), Eigen::Vector2d(0, 0));
    EXPECT_EQ(plan.maxCorner(), Eigen::Vector2d(10, 0));
}
