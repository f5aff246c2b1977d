#pragma once

#include <mrpt/obs/CObservationIMU.h>

#include <Eigen/Geometry>
#include <deque>
#include <optional>

namespace lodestone::odometry {

/** A rate gyro's samples (CObservationIMU's IMU_WX..WZ, sensor frame) integrated between two
 * instants: the rotation of the sensor's body from t0 to t1 (R_t0_t1, each sample the rate at
 * its instant, linear between two, held after the last), and how uncertain it is - the white
 * noise summed over the interval, plus the bias left after `bias` grown with time. */
class GyroIntegrator {
  public:
    struct Params {
        double noiseStd{0.07 * M_PI / 180};  ///< per-axis white noise of a sample [rad/s]
        double biasStd{0.1 * M_PI / 180};    ///< per-axis bias not removed [rad/s]
        double maxGap{0.1};                  ///< samples further apart do not cover [s]
    };
    struct Rotation {
        Eigen::Matrix3d R;  ///< body at t1 in body at t0
        double sigma{0};    ///< per-axis [rad]
    };

    GyroIntegrator() = default;
    explicit GyroIntegrator(const Params& params) : params_(params) {}

    /** Takes a sample; one without all three rates, non-finite, or older than the last is
     * skipped (false). */
    bool add(const mrpt::obs::CObservationIMU& imu);
    /** R_t0_t1, or nothing when the samples do not cover [t0, t1] (a gap, not yet received). */
    std::optional<Rotation> between(double t0, double t1) const;
    /** The bias to take out of every sample from now on [rad/s, sensor frame], and how well it
     * is known per axis (replaces Params::biasStd in the sigma). */
    void setBias(const Eigen::Vector3d& bias, double biasStd);
    /** Forgets samples older than t (keeps the one in force at t). */
    void dropBefore(double t);
    /** The sensor's pose on the robot, from its samples. */
    const Eigen::Isometry3d& sensorOnRobot() const { return sensor_on_robot_; }
    std::size_t size() const { return samples_.size(); }

  private:
    struct Sample {
        double t;
        Eigen::Vector3d w;
    };
    Params params_;
    Eigen::Vector3d bias_{Eigen::Vector3d::Zero()};
    std::deque<Sample> samples_;
    Eigen::Isometry3d sensor_on_robot_{Eigen::Isometry3d::Identity()};
};

}  // namespace lodestone::odometry
