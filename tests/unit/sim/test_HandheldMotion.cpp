// The hand-held camera's motion about its carrier's path: at the given height, within its
// bob, sway and shake, smooth, and the same for the same seed.
#include <gtest/gtest.h>
#include <lodestone/sim/HandheldMotion.h>

#include "SimTestWorlds.h"

using namespace lodestone::sim;

TEST(HandheldMotion, RidesTheCarriersPathWithinItsShake) {
    const Scenario sc = lodestone::test::boxScenario();
    const MotionPlan plan(sc.motion, {}, [](const Eigen::Vector2d&, const Eigen::Vector2d&) { return true; });
    const HandheldSpec spec;
    const HandheldMotion hand(plan, spec, Random(4)), again(plan, spec, Random(4)),
        other(plan, spec, Random(5));
    double maxTilt = 0, maxStep = 0, differs = 0;
    Eigen::Isometry3d prev = hand.poseAt(0);
    for (double t = 0; t < plan.duration(); t += 1.0 / 30) {
        const Eigen::Isometry3d T = hand.poseAt(t);
        const RobotPose p = plan.poseAt(t);
        EXPECT_NEAR(T.translation().z(), spec.height, 1.5 * spec.bob + 1e-9);
        EXPECT_LT(std::hypot(T.translation().x() - p.x, T.translation().y() - p.y), 1.5 * spec.sway + 1e-9);
        // Tilt: the angle between the camera's up and the world's.
        maxTilt = std::max(maxTilt, std::acos(std::clamp(T.linear()(2, 2), -1.0, 1.0)));
        maxStep = std::max(maxStep, (T.translation() - prev.translation()).norm());
        EXPECT_TRUE(T.isApprox(again.poseAt(t)));  // deterministic for a seed
        differs = std::max(differs, (T.translation() - other.poseAt(t).translation()).norm());
        prev = T;
    }
    const double shake = spec.shakeDeg * M_PI / 180;
    EXPECT_GT(maxTilt, 0.2 * shake);  // it does shake ...
    EXPECT_LT(maxTilt, 3.0 * shake);  // ... moderately
    EXPECT_LT(maxStep, 0.1);          // smooth at 30 Hz: no jumps
    EXPECT_GT(differs, 1e-3);         // another seed, another hand
}
