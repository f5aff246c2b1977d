#pragma once

#include <mrpt/poses/CPosePDFGaussian.h>

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <string>

namespace lodestone::odometry {

/** One synchronized step of the two odometries over the same interval: the wheels' motion and,
 * when visual odometry produced one, the camera's, both as planar motions of the robot in the
 * frame of the pose at the start of the interval. */
struct OdometryStep {
    mrpt::poses::CPosePDFGaussian wheel;
    std::optional<mrpt::poses::CPosePDFGaussian> visual;  ///< none: VO failed or LOST
    double dt{0};                                         ///< [s]
};

/** A way of combining wheel and visual odometry into one planar trajectory. */
class PlanarFusion {
  public:
    virtual ~PlanarFusion() = default;
    /** Takes one step; returns the fused pose after it. */
    virtual const mrpt::poses::CPosePDFGaussian& step(const OdometryStep& s) = 0;
    virtual const mrpt::poses::CPosePDFGaussian& pose() const = 0;
    virtual void reset(const mrpt::poses::CPosePDFGaussian& start) = 0;
    virtual std::string name() const = 0;
    /** The motion the last step() applied, in the frame of the pose before it, with its
     * covariance: what a pose graph takes as the odometry between two of its nodes. */
    const mrpt::poses::CPosePDFGaussian& lastIncrement() const { return increment_; }
    /** How the last increment moves with its step's wheel motion, to first order (x, y, phi
     * by x, y, phi): the identity where the wheels alone moved it, less where VO shared. */
    const Eigen::Matrix3d& lastWheelGain() const { return wheel_gain_; }

  protected:
    mrpt::poses::CPosePDFGaussian increment_;
    Eigen::Matrix3d wheel_gain_{Eigen::Matrix3d::Identity()};
};

/** Creates a fusion by name: "wheel" (wheels only), "visual" (VO only: no motion while it
 * fails), "covariance" (information-weighted increments on SE(2), VO dropped while LOST) or
 * "kalman" (paper 003 §4, eq. 2, with weight `kalmanWeight` on the wheels). Throws
 * std::invalid_argument naming an unknown method. */
std::unique_ptr<PlanarFusion> makePlanarFusion(const std::string& method, double kalmanWeight = 0.7,
                                               double kalmanProcessNoise = 0.5,
                                               double kalmanMeasurementNoise = 1e-4);

}  // namespace lodestone::odometry
