#include <lodestone/sim/SimSensor.h>

#include <chrono>
#include <limits>

namespace lodestone::sim {

mrpt::Clock::time_point simTimestamp(double startTime, std::int64_t tNs) {
    return mrpt::Clock::fromDouble(startTime) +
           std::chrono::duration_cast<mrpt::Clock::duration>(std::chrono::nanoseconds(tNs));
}

std::int64_t SampleClock::nextWithin(double duration) const {
    return now() * 1e-9 <= duration ? now() : std::numeric_limits<std::int64_t>::max();
}

SensorWorldPose sensorInWorld(const RobotPose& robot, double mx, double my, double mz,
                              double myaw) {
    const double c = std::cos(robot.yaw), s = std::sin(robot.yaw);
    return {{robot.x + c * mx - s * my, robot.y + s * mx + c * my, robot.z + mz}, robot.yaw + myaw};
}

}  // namespace lodestone::sim
