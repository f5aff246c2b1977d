#pragma once

#include <lodestone/sim/HandheldMotion.h>
#include <lodestone/sim/Random.h>
#include <lodestone/sim/Scenario.h>
#include <lodestone/sim/SimSensor.h>

namespace lodestone::sim {

/** A 3-axis rate gyro as stock MRPT's CObservationIMU (IMU_WX, IMU_WY, IMU_WZ [rad/s], in the
 * sensor frame): the carrier's true angular velocity - the robot's yaw rate, or a hand-held
 * camera's body rate (the gyro rigid with it) - plus a constant bias drawn per run and white
 * noise. */
class SimGyro : public SimSensor {
  public:
    /** With `handheld`, the gyro is the camera's (sensorPose identity, as the camera's). */
    SimGyro(const MotionPlan& plan, const HandheldMotion* handheld, const GyroSpec& spec,
            double startTime, Random rng);
    std::int64_t nextTimeNs() const override;
    mrpt::obs::CObservation::Ptr produce() override;
    /** The true angular velocity at t [rad/s], sensor frame (for tests). */
    Eigen::Vector3d trueRate(double t) const;
    const Eigen::Vector3d& bias() const { return bias_; }

  private:
    const MotionPlan& plan_;
    const HandheldMotion* handheld_;
    GyroSpec spec_;
    double start_time_;
    Random rng_;
    SampleClock clock_;
    Eigen::Vector3d bias_;
};

}  // namespace lodestone::sim
