#pragma once

#include <lodestone/sim/HandheldMotion.h>
#include <lodestone/sim/Random.h>
#include <lodestone/sim/Scenario.h>
#include <lodestone/sim/SimSensor.h>

namespace lodestone::sim {

/** An IMU as stock MRPT's CObservationIMU, in the sensor frame: the rate gyro (IMU_WX..WZ
 * [rad/s]) reads the carrier's true angular velocity - the robot's yaw rate, or a hand-held
 * camera's body rate (the IMU rigid with it) - and the accelerometer (IMU_X_ACC..Z_ACC
 * [m/s^2]) the specific force, the sensor's acceleration less gravity (at rest: 9.81 up);
 * each plus a constant bias drawn per run and white noise. */
class SimGyro : public SimSensor {
  public:
    /** With `handheld`, the gyro is the camera's (sensorPose identity, as the camera's). */
    SimGyro(const MotionPlan& plan, const HandheldMotion* handheld, const GyroSpec& spec,
            double startTime, Random rng);
    std::int64_t nextTimeNs() const override;
    mrpt::obs::CObservation::Ptr produce() override;
    /** The true angular velocity at t [rad/s], sensor frame (for tests). */
    Eigen::Vector3d trueRate(double t) const;
    /** The true specific force at t [m/s^2], sensor frame (for tests). */
    Eigen::Vector3d trueSpecificForce(double t) const;
    const Eigen::Vector3d& bias() const { return bias_; }
    const Eigen::Vector3d& accelBias() const { return accel_bias_; }

  private:
    const MotionPlan& plan_;
    const HandheldMotion* handheld_;
    GyroSpec spec_;
    double start_time_;
    /** World <- sensor at t. */
    Eigen::Isometry3d sensorPoseAt(double t) const;

    Random rng_, accel_rng_;  // (the accelerometer's own stream: the gyro's draws unchanged)
    SampleClock clock_;
    Eigen::Vector3d bias_, accel_bias_;
};

}  // namespace lodestone::sim
