#pragma once

#include <lodestone/sim/MotionPlan.h>
#include <mrpt/obs/CObservation.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace lodestone::sim {

/** A simulated sensor: it knows when its next sample is due and produces it. Samples are
 * produced in time order, so a sensor may keep state (encoder counts, noise streams). */
class SimSensor {
  public:
    virtual ~SimSensor() = default;
    /** Time of the next sample [ns since the scenario start]; INT64_MAX when done. */
    virtual std::int64_t nextTimeNs() const = 0;
    /** The sample at nextTimeNs(); advances to the following one. */
    virtual mrpt::obs::CObservation::Ptr produce() = 0;
};

/** Scenario time [ns] -> timestamp, exact to MRPT's 100 ns clock tick. */
mrpt::Clock::time_point simTimestamp(double startTime, std::int64_t tNs);

/** The sampling instants of a fixed-rate sensor: k * period, period rounded to 1 ns. */
struct SampleClock {
    explicit SampleClock(double rateHz)
        : periodNs(static_cast<std::int64_t>(std::llround(1e9 / rateHz))) {}
    std::int64_t periodNs;
    std::int64_t k{0};
    std::int64_t now() const { return k * periodNs; }
    /** now(), or INT64_MAX once past `duration` [s]: the sensor is done. */
    std::int64_t nextWithin(double duration) const;
};

/** World pose of a sensor mounted level at (x, y, z, yaw) on the robot. */
struct SensorWorldPose {
    Eigen::Vector3d position;
    double yaw;
};
SensorWorldPose sensorInWorld(const RobotPose& robot, double mx, double my, double mz, double myaw);

}  // namespace lodestone::sim
