#include <lodestone/odometry/CovarianceWeightedFusion.h>

#include <Eigen/Dense>
#include <cmath>

namespace lodestone::odometry {

namespace {
Eigen::Vector3d vec(const mrpt::poses::CPose2D& p) { return {p.x(), p.y(), p.phi()}; }
}  // namespace

mrpt::poses::CPosePDFGaussian CovarianceWeightedFusion::combine(
    const mrpt::poses::CPosePDFGaussian& a, const mrpt::poses::CPosePDFGaussian& b) {
    // A tiny floor keeps an exactly-zero covariance (no motion, no noise) invertible.
    const Eigen::Matrix3d floor = 1e-12 * Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d Ia = (a.cov.asEigen() + floor).inverse();
    const Eigen::Matrix3d Ib = (b.cov.asEigen() + floor).inverse();
    const Eigen::Matrix3d C = (Ia + Ib).inverse();
    Eigen::Vector3d mb = vec(b.mean);
    mb.z() = a.mean.phi() + std::remainder(mb.z() - a.mean.phi(), 2 * M_PI);
    const Eigen::Vector3d m = C * (Ia * vec(a.mean) + Ib * mb);
    mrpt::poses::CPosePDFGaussian out;
    out.mean = mrpt::poses::CPose2D(m.x(), m.y(), m.z());
    out.cov = mrpt::math::CMatrixDouble33(C);
    return out;
}

const mrpt::poses::CPosePDFGaussian& CovarianceWeightedFusion::step(const OdometryStep& s) {
    increment_ = s.visual ? combine(s.wheel, *s.visual) : s.wheel;
    // combine()'s mean is C (I_w w + I_v v): its gain on the wheels' step is C I_w.
    wheel_gain_ = Eigen::Matrix3d::Identity();
    if (s.visual) {
        const Eigen::Matrix3d floor = 1e-12 * Eigen::Matrix3d::Identity();
        wheel_gain_ = increment_.cov.asEigen() * (s.wheel.cov.asEigen() + floor).inverse();
    }
    pose_ += increment_;
    return pose_;
}

}  // namespace lodestone::odometry
