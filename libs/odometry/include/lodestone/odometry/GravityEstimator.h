#pragma once

#include <mrpt/obs/CObservationIMU.h>

#include <Eigen/Geometry>
#include <deque>
#include <optional>

namespace lodestone::odometry {

/** Which way is up, from an IMU's accelerometer: the specific force (IMU_X_ACC..Z_ACC) averaged
 * over the last `windowSeconds`, each sample turned into the sensor's frame at the end of the
 * window by the gyro (IMU_WX..WZ of the same samples, held over each interval), so a turn
 * inside the window does not smear it. At rest or at constant velocity the mean is gravity's
 * reaction, 9.81 m/s^2 up; the carrier's own accelerations average out over the window as far
 * as they change sign within it.
 *
 * Its uncertainty, per axis of the unit vector [rad]: the accelerometer's residual bias
 * (`biasStd`, common to every window) and the mean's scatter - the samples' spread about their
 * mean (noise and the carrier's accelerations) over the number of independent samples the
 * window holds, at most one per `motionSeconds` (how long a carrier's acceleration keeps its
 * sign: a gait's or a hand's half period). What does not average out - the carrier speeding
 * up, slowing down or turning over the window - is the window's mean acceleration, the change
 * of its velocity over the window's length: the caller gives it (from its odometry's
 * velocities) with its uncertainty, and it is taken out. A window whose mean is not near 1 g
 * (the carrier accelerating hard, or falling) gives nothing. */
class GravityEstimator {
  public:
    struct Params {
        double windowSeconds{1.0};   ///< [s] averaged
        double motionSeconds{0.25};  ///< [s] a carrier's acceleration keeps its sign this long
        double biasStd{0.02};        ///< per-axis accelerometer bias not removed [m/s^2]
        double maxGap{0.1};          ///< samples further apart do not cover [s]
    };
    struct Up {
        Eigen::Vector3d up;  ///< unit, the sensor's frame at t
        double sigma{0};     ///< per axis [rad]
        int samples{0};
    };

    GravityEstimator() = default;
    explicit GravityEstimator(const Params& params) : params_(params) {}

    /** Takes a sample with all three rates and accelerations (false: skipped, as one that is
     * non-finite or older than the last). */
    bool add(const mrpt::obs::CObservationIMU& imu);
    /** Up in the sensor's frame at t (the last sample at or before t), or nothing when the
     * samples do not cover the window or its mean is not near 1 g. `meanAcceleration`: the
     * carrier's mean acceleration over the window (the sensor's frame at t) [m/s^2], known to
     * `accelerationSigma` per axis. */
    std::optional<Up> at(double t,
                         const Eigen::Vector3d& meanAcceleration = Eigen::Vector3d::Zero(),
                         double accelerationSigma = 0) const;
    /** Forgets samples older than t - windowSeconds. */
    void dropBefore(double t);
    /** The sensor's pose on the robot, from its samples. */
    const Eigen::Isometry3d& sensorOnRobot() const { return sensor_on_robot_; }
    std::size_t size() const { return samples_.size(); }

    static constexpr double kGravity = 9.81;  ///< [m/s^2]

  private:
    struct Sample {
        double t;
        Eigen::Vector3d w, f;
    };
    Params params_;
    std::deque<Sample> samples_;
    Eigen::Isometry3d sensor_on_robot_{Eigen::Isometry3d::Identity()};
};

}  // namespace lodestone::odometry
