#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace lodestone::sim {

/** The robot's pose: planar, plus the height it is lifted to while kidnapped. */
struct RobotPose {
    double x{0}, y{0}, yaw{0};  ///< [m, m, rad]
    double z{0};                ///< lift above the floor [m]; 0 on the ground
};

/** One piece of motion with a closed-form pose at any time in [t0, t1]. */
struct MotionSegment {
    enum class Kind { Rotate, Drive, Carry, Wait };
    Kind kind{Kind::Wait};
    double t0{0}, t1{0};  ///< [s] since the scenario start
    RobotPose start, end;
    double liftHeight{0};  ///< Carry: peak lift [m]
};

/** The pose on segment `s` at time t (clamped to [t0, t1]). */
RobotPose poseOnSegment(const MotionSegment& s, double t);

/** A kidnap: at `start` the robot is lifted, carried for `duration` and put down at `putDown`.
 */
struct KidnapSpec {
    std::string name;              ///< the INI key, for messages
    double start{0}, duration{0};  ///< [s]
    RobotPose putDown;
    double liftHeight{0.4};  ///< [m]
};

/** What a differential-drive base does: rotate in place towards the next waypoint, drive
 * straight to it, round the closed loop of waypoints `laps` times. Kidnaps interrupt it; after
 * a put-down the robot drives to the nearest waypoint it can reach in a straight line and
 * carries on round the loop from there. All poses and wheel angles are closed-form in time. */
class MotionPlan {
  public:
    struct Params {
        std::vector<Eigen::Vector2d> waypoints;  ///< a closed loop [m]
        int laps{1};
        double speed{0.3};          ///< [m/s]
        double turnRate{0.6};       ///< [rad/s]
        double wheelBase{0.23};     ///< distance between the wheels [m]
        double wheelRadius{0.035};  ///< [m]
    };

    /** Plans the motion. `reachable(a, b)` says whether the robot may drive straight from a to
     * b; a kidnap whose put-down reaches no waypoint throws std::invalid_argument naming it. */
    MotionPlan(
        const Params& params, const std::vector<KidnapSpec>& kidnaps,
        const std::function<bool(const Eigen::Vector2d&, const Eigen::Vector2d&)>& reachable);

    RobotPose poseAt(double t) const;
    /** Total rotation of the left / right wheel since the start [rad], positive forward. */
    Eigen::Vector2d wheelAnglesAt(double t) const;
    /** Velocity in the robot frame at t: forward [m/s] and yaw rate [rad/s]. */
    Eigen::Vector2d velocityAt(double t) const;
    /** True while the robot is off the ground (carried). */
    bool liftedAt(double t) const;

    double duration() const { return segments_.empty() ? 0 : segments_.back().t1; }
    const std::vector<MotionSegment>& segments() const { return segments_; }
    const Params& params() const { return params_; }

  private:
    const MotionSegment& segmentAt(double t) const;
    void append(MotionSegment s);

    Params params_;
    std::vector<MotionSegment> segments_;
    std::vector<Eigen::Vector2d> wheel_at_start_;  // wheel angles at each segment's t0
};

}  // namespace lodestone::sim
