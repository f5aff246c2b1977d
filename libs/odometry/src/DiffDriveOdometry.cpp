#include <lodestone/config/IniSection.h>
#include <lodestone/odometry/DiffDriveOdometry.h>
#include <mrpt/poses/CPosePDF.h>

#include <Eigen/Core>
#include <cmath>
#include <ostream>

namespace lodestone::odometry {

void DiffDriveOdometry::Params::loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                                   const std::string& section) {
    config::IniSection s(source, section, config::sourceName(source));
    wheelBase = s.getDouble("wheel_base", wheelBase);
    wheelRadius = s.getDouble("wheel_radius", wheelRadius);
    ticksPerRev = s.getDouble("ticks_per_rev", ticksPerRev);
    wheelNoise = s.getDouble("wheel_noise", wheelNoise);
    if (wheelBase <= 0) s.fail("wheel_base", "must be > 0");
    if (wheelRadius <= 0) s.fail("wheel_radius", "must be > 0");
    if (ticksPerRev <= 0) s.fail("ticks_per_rev", "must be > 0");
    if (wheelNoise < 0) s.fail("wheel_noise", "must be >= 0");
    s.finish();
}

void DiffDriveOdometry::Params::dumpToTextStream(std::ostream& out) const {
    out << "wheel_base    = " << wheelBase << "  [m]\n"
        << "wheel_radius  = " << wheelRadius << "  [m]\n"
        << "ticks_per_rev = " << ticksPerRev << "\n"
        << "wheel_noise   = " << wheelNoise << "  [m^2 per m of travel]\n";
}

DiffDriveOdometry::DiffDriveOdometry() : DiffDriveOdometry(Params()) {}

DiffDriveOdometry::DiffDriveOdometry(const Params& params) : params_(params) {}

void DiffDriveOdometry::reset(const mrpt::poses::CPosePDFGaussian& pose) {
    pose_ = pose;
    last_ticks_.reset();
}

mrpt::poses::CPosePDFGaussian DiffDriveOdometry::stepFromOrigin(double dl, double dr,
                                                                const Params& p) {
    const double b = p.wheelBase;
    const double ds = 0.5 * (dr + dl), dphi = (dr - dl) / b, mid = 0.5 * dphi;
    const double c = std::cos(mid), s = std::sin(mid);
    mrpt::poses::CPosePDFGaussian step;
    step.mean = mrpt::poses::CPose2D(ds * c, ds * s, dphi);
    // Jacobian of eq. (1) (from Φ = 0) with respect to (Δs_r, Δs_l).
    Eigen::Matrix<double, 3, 2> G;
    G << 0.5 * c - ds * s / (2 * b), 0.5 * c + ds * s / (2 * b),  //
        0.5 * s + ds * c / (2 * b), 0.5 * s - ds * c / (2 * b),   //
        1.0 / b, -1.0 / b;
    const Eigen::Matrix2d Q =
        Eigen::Vector2d(p.wheelNoise * std::abs(dr), p.wheelNoise * std::abs(dl)).asDiagonal();
    const Eigen::Matrix3d cov = G * Q * G.transpose();
    step.cov = mrpt::math::CMatrixDouble33(cov);
    return step;
}

Eigen::Matrix<double, 3, 2> DiffDriveOdometry::scaleJacobian(double dl, double dr,
                                                             const Params& p) {
    const double b = p.wheelBase;
    const double ds = 0.5 * (dr + dl), mid = 0.5 * (dr - dl) / b;
    const double c = std::cos(mid), s = std::sin(mid);
    // d(x, y, phi)/d(Δs_l) and d/d(Δs_r) of eq. (1), each times its wheel's travel.
    Eigen::Matrix<double, 3, 2> J;
    J << (0.5 * c + ds * s / (2 * b)) * dl, (0.5 * c - ds * s / (2 * b)) * dr,  //
        (0.5 * s - ds * c / (2 * b)) * dl, (0.5 * s + ds * c / (2 * b)) * dr,   //
        -dl / b, dr / b;
    return J;
}

Eigen::Matrix<double, 3, 2> DiffDriveOdometry::composeScaleJacobian(
    const mrpt::poses::CPose2D& before, const Eigen::Matrix<double, 3, 2>& beforeJacobian,
    const mrpt::poses::CPose2D& step, const Eigen::Matrix<double, 3, 2>& stepJacobian) {
    // d(before + step) / d(before) and / d(step): MRPT's Jacobians of the composition.
    mrpt::math::CMatrixDouble33 A, B;
    mrpt::poses::CPosePDF::jacobiansPoseComposition(before, step, A, B);
    return A.asEigen() * beforeJacobian + B.asEigen() * stepJacobian;
}

DiffDriveOdometry::Increment DiffDriveOdometry::addTravel(double leftTravel, double rightTravel) {
    Increment inc;
    inc.leftTravel = leftTravel;
    inc.rightTravel = rightTravel;
    inc.motion = stepFromOrigin(leftTravel, rightTravel, params_);
    pose_ += inc.motion;  // composition with first-order covariance propagation
    return inc;
}

std::optional<DiffDriveOdometry::Increment> DiffDriveOdometry::addTicks(std::int32_t left,
                                                                        std::int32_t right) {
    if (!last_ticks_) {
        last_ticks_ = {left, right};
        return std::nullopt;
    }
    // Unsigned subtraction wraps modulo 2^32: a counter that rolled over gives the small step.
    const auto delta = [](std::int32_t now, std::int32_t before) {
        return static_cast<std::int32_t>(static_cast<std::uint32_t>(now) -
                                         static_cast<std::uint32_t>(before));
    };
    const double metresPerTick = 2 * M_PI * params_.wheelRadius / params_.ticksPerRev;
    const double dl = delta(left, last_ticks_->first) * metresPerTick;
    const double dr = delta(right, last_ticks_->second) * metresPerTick;
    last_ticks_ = {left, right};
    return addTravel(dl, dr);
}

}  // namespace lodestone::odometry
