#pragma once

#include <lodestone/odometry/PlanarFusion.h>

#include <Eigen/Core>

namespace lodestone::odometry {

/** The Kalman filter of paper 003 §4. Each source keeps its own track (x_wheel, x_visual) and
 * the measurement is eq. (2):
 *   z_k = [ C x_wheel,k + (1-C) x_visual,k ;
 *           (C (x_wheel,k - x_wheel,k-1) + (1-C)(x_visual,k - x_visual,k-1)) / Δt ],
 * a position and a velocity weighted C towards the short-term accurate wheels, filtered with a
 * constant-velocity model per axis (x, y, heading). While VO has no estimate its track follows
 * the wheels', so the blend degrades gracefully to wheel odometry instead of jumping. */
class KalmanFusion : public PlanarFusion {
  public:
    KalmanFusion(double weightC, double processNoise, double measurementNoise);
    const mrpt::poses::CPosePDFGaussian& step(const OdometryStep& s) override;
    const mrpt::poses::CPosePDFGaussian& pose() const override { return pose_; }
    void reset(const mrpt::poses::CPosePDFGaussian& start) override;
    std::string name() const override { return "kalman"; }

  private:
    double c_, q_, r_;
    mrpt::poses::CPose2D wheel_, visual_;       // the two tracks
    Eigen::Vector3d last_wheel_, last_visual_;  // unwrapped (x, y, heading)
    Eigen::Matrix<double, 2, 3> state_;         // per axis: position, velocity
    Eigen::Matrix<double, 2, 6> cov_;           // per axis: 2x2 covariance, side by side
    mrpt::poses::CPosePDFGaussian pose_;
    bool started_{false};
};

}  // namespace lodestone::odometry
