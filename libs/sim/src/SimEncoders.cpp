#include <lodestone/sim/SimEncoders.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <cmath>

namespace lodestone::sim {

SimEncoders::SimEncoders(const MotionPlan& plan, const EncoderSpec& spec, double startTime,
                         Random rng)
    : plan_(plan), spec_(spec), start_time_(startTime), rng_(rng), clock_(spec.rate) {
    const RobotPose p0 = plan.poseAt(0);
    x_ = p0.x;
    y_ = p0.y;
    yaw_ = p0.yaw;
}

std::int64_t SimEncoders::nextTimeNs() const { return clock_.nextWithin(plan_.duration()); }

mrpt::obs::CObservation::Ptr SimEncoders::produce() {
    const std::int64_t tNs = clock_.now();
    ++clock_.k;
    const double t = tNs * 1e-9;
    const Eigen::Vector2d wheels = plan_.wheelAnglesAt(t);
    const Eigen::Vector2d step =
        first_ ? Eigen::Vector2d::Zero() : Eigen::Vector2d(wheels - last_true_);
    first_ = false;
    last_true_ = wheels;
    const double scale[2] = {spec_.leftScale, spec_.rightScale};
    for (int i = 0; i < 2; ++i) {
        const double slip = step[i] != 0.0 ? spec_.slipStd * rng_.normal() : 0.0;
        measured_[i] += step[i] * scale[i] * (1.0 + slip);
    }
    const Eigen::Vector2i ticks(
        static_cast<int>(std::floor(measured_[0] / (2 * M_PI) * spec_.ticksPerRev)),
        static_cast<int>(std::floor(measured_[1] / (2 * M_PI) * spec_.ticksPerRev)));

    // The base's own odometry from the tick increments (midpoint integration).
    const double metresPerTick = 2 * M_PI * plan_.params().wheelRadius / spec_.ticksPerRev;
    const double dl = (ticks[0] - last_ticks_[0]) * metresPerTick;
    const double dr = (ticks[1] - last_ticks_[1]) * metresPerTick;
    last_ticks_ = ticks;
    const double ds = 0.5 * (dl + dr), dyaw = (dr - dl) / plan_.params().wheelBase;
    x_ += ds * std::cos(yaw_ + 0.5 * dyaw);
    y_ += ds * std::sin(yaw_ + 0.5 * dyaw);
    yaw_ = std::atan2(std::sin(yaw_ + dyaw), std::cos(yaw_ + dyaw));

    auto obs = mrpt::obs::CObservationOdometry::Create();
    obs->timestamp = simTimestamp(start_time_, tNs);
    obs->sensorLabel = spec_.label;
    obs->odometry = mrpt::poses::CPose2D(x_, y_, yaw_);
    obs->hasEncodersInfo = true;
    obs->encoderLeftTicks = ticks[0];
    obs->encoderRightTicks = ticks[1];
    obs->hasVelocities = true;
    const Eigen::Vector2d v = plan_.velocityAt(t);
    obs->velocityLocal = mrpt::math::TTwist2D(v[0], 0, v[1]);
    return obs;
}

}  // namespace lodestone::sim
