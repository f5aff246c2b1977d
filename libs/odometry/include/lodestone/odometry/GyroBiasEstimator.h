#pragma once

#include <Eigen/Geometry>

namespace lodestone::odometry {

/** A rate gyro's bias, estimated where another sensor measures the same rotations (VO while it
 * tracks): a constant bias per axis, each interval's rotation difference over its length a
 * measurement of what is left of it (a Kalman filter, isotropic). A measurement the estimate
 * contradicts at chi-square 99.9 % (3 dof) is the other sensor's outlier and is skipped. */
class GyroBiasEstimator {
  public:
    /** priorStd: the bias a calibrated gyro may still have, per axis [rad/s]. */
    explicit GyroBiasEstimator(double priorStd = 0.1 * M_PI / 180)
        : variance_(priorStd * priorStd) {}

    /** Over one interval of `seconds`: the gyro's rotation with the current estimate taken out
     * and the other sensor's (both R_t0_t1 in the gyro's body frame), that one's sigma per axis
     * [rad]. False when skipped (an outlier, or an interval of no length). */
    bool update(const Eigen::Matrix3d& gyro, const Eigen::Matrix3d& measured, double measuredSigma,
                double seconds);

    const Eigen::Vector3d& bias() const { return bias_; }  ///< [rad/s]
    double sigma() const;                                  ///< per axis [rad/s]
    int updates() const { return updates_; }
    int skipped() const { return skipped_; }

  private:
    Eigen::Vector3d bias_{Eigen::Vector3d::Zero()};
    double variance_;
    int updates_{0}, skipped_{0};
};

}  // namespace lodestone::odometry
