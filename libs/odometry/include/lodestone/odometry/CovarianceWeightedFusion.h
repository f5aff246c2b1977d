#pragma once

#include <lodestone/odometry/PlanarFusion.h>

namespace lodestone::odometry {

/** Fuses each step's two motion estimates by their information (inverse covariances) — the
 * maximum-likelihood combination of two Gaussian measurements of the same SE(2) increment,
 * linearized at the wheel estimate (increments are small) — and composes the result onto the
 * pose. Without a visual estimate the wheel step is taken as is. */
class CovarianceWeightedFusion : public PlanarFusion {
  public:
    const mrpt::poses::CPosePDFGaussian& step(const OdometryStep& s) override;
    const mrpt::poses::CPosePDFGaussian& pose() const override { return pose_; }
    void reset(const mrpt::poses::CPosePDFGaussian& start) override { pose_ = start; }
    std::string name() const override { return "covariance"; }

    /** The information-weighted mean and covariance of two estimates of one increment. */
    static mrpt::poses::CPosePDFGaussian combine(const mrpt::poses::CPosePDFGaussian& a,
                                                 const mrpt::poses::CPosePDFGaussian& b);

  private:
    mrpt::poses::CPosePDFGaussian pose_;
};

}  // namespace lodestone::odometry
