#pragma once

#include <lodestone/sim/MotionPlan.h>
#include <lodestone/sim/Random.h>
#include <lodestone/sim/Scenario.h>

#include <Eigen/Geometry>
#include <array>

namespace lodestone::sim {

/** A handheld camera's 6-DoF pose: the carrier walks the scenario's path (MotionPlan: x, y,
 * heading), the camera at `height` bobs, sways and shakes about it - each of the six a sum of
 * three sinusoids of 0.3-2 Hz with random phases (smooth, like a hand; deterministic for a
 * seed). The pose is the camera's in MRPT's depth frame (x forward, y left, z up); with it the
 * camera is the robot (sensorPose identity), as in RGB-D datasets. */
class HandheldMotion {
  public:
    HandheldMotion(const MotionPlan& plan, const HandheldSpec& spec, Random rng);
    /** World <- camera at time t [s]. */
    Eigen::Isometry3d poseAt(double t) const;

  private:
    struct Wave {
        double amplitude, frequency, phase;
    };
    double offset(int axis, double t) const;  // axis 0-5: sway, bob, (unused), yaw, pitch, roll

    const MotionPlan& plan_;
    HandheldSpec spec_;
    std::array<std::array<Wave, 3>, 6> waves_;
};

}  // namespace lodestone::sim
