#include <lodestone/odometry/FadingVelocity.h>

#include <algorithm>
#include <cmath>

namespace lodestone::odometry {

Eigen::Vector3d FadingVelocity::meanDisplacement(const Eigen::Vector3d& v0, double seconds,
                                                 const Eigen::Vector3d& cruise) const {
    const double T = std::max(0.0, seconds);
    const double along = step(T).carry, side = across().step(T).carry;
    const Eigen::Vector3d carry(along, side, side);
    // (the deviation from the cruise fades; the cruise goes on)
    return carry.cwiseProduct(v0 - cruise) + T * cruise;
}

void FadingVelocity::fadeVelocity(double seconds, Eigen::Vector3d& v, Eigen::Matrix3d& C,
                                  const Eigen::Vector3d& cruise) const {
    const Step along = step(seconds), side = across().step(seconds);
    const Eigen::Vector3d fade(along.fade, side.fade, side.fade);
    v = cruise + fade.cwiseProduct(v - cruise);
    C = fade.asDiagonal() * C * fade.asDiagonal();
    C.diagonal() += Eigen::Vector3d(along.qvv, side.qvv, side.qvv);
}

FadingVelocity FadingVelocity::across() const {
    return {speedSigma, acrossSeconds > 0 ? acrossSeconds : correlationSeconds};
}

Eigen::Vector3d FadingVelocity::displacementVariances(double seconds, double v0Sigma) const {
    const double across = this->across().displacementVariance(seconds, v0Sigma);
    return Eigen::Vector3d(displacementVariance(seconds, v0Sigma), across, across);
}

double FadingVelocity::displacementVariance(double seconds, double v0Sigma) const {
    // (along the heading: `correlationSeconds`)
    const double tau = correlationSeconds, u = std::max(0.0, seconds) / tau;
    // For small u the bracket cancels to 2 u^3 / 3: take the series there (no cancellation).
    const double bracket =
        u < 1e-3 ? 2.0 * u * u * u / 3.0 : 2 * u - 3 + 4 * std::exp(-u) - std::exp(-2 * u);
    const double carried = tau * -std::expm1(-u) * v0Sigma;  // (the start velocity's own error)
    return speedSigma * speedSigma * tau * tau * bracket + carried * carried;
}

FadingVelocity::Step FadingVelocity::step(double seconds) const {
    const double tau = correlationSeconds, s2 = speedSigma * speedSigma;
    const double u = std::max(0.0, seconds) / tau, a = std::exp(-u);
    const double bracket = u < 1e-3 ? 2.0 * u * u * u / 3.0 : 2 * u - 3 + 4 * a - a * a;
    Step s;
    s.fade = a;
    s.carry = tau * -std::expm1(-u);
    s.qxx = s2 * tau * tau * bracket;
    s.qvv = s2 * -std::expm1(-2 * u);
    s.qxv = s2 * tau * std::pow(-std::expm1(-u), 2);
    return s;
}

void FadingVelocity::Step::matrices(Eigen::Matrix<double, 9, 9>& F,
                                    Eigen::Matrix<double, 9, 9>& Q) const {
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    F.setIdentity();
    F.block<3, 3>(0, 3) = carry * I;
    F.block<3, 3>(3, 3) = fade * I;
    Q.setZero();
    Q.block<3, 3>(0, 0) = qxx * I;
    Q.block<3, 3>(3, 3) = qvv * I;
    Q.block<3, 3>(0, 3) = Q.block<3, 3>(3, 0) = qxv * I;
}

void FadingVelocity::matrices(double seconds, const Eigen::Matrix3d& R,
                              Eigen::Matrix<double, 9, 9>& F, Eigen::Matrix<double, 9, 9>& Q) const {
    const Step along = step(seconds);
    if (!(acrossSeconds > 0)) {
        along.matrices(F, Q);
        return;
    }
    const Step side = across().step(seconds);
    // Each of the step's terms is diagonal in the carrier's axes: R diag R^T in the state's.
    const auto turned = [&R](double a, double s) -> Eigen::Matrix3d {
        return R * Eigen::Vector3d(a, s, s).asDiagonal() * R.transpose();
    };
    F.setIdentity();
    F.block<3, 3>(0, 3) = turned(along.carry, side.carry);
    F.block<3, 3>(3, 3) = turned(along.fade, side.fade);
    Q.setZero();
    Q.block<3, 3>(0, 0) = turned(along.qxx, side.qxx);
    Q.block<3, 3>(3, 3) = turned(along.qvv, side.qvv);
    Q.block<3, 3>(0, 3) = Q.block<3, 3>(3, 0) = turned(along.qxv, side.qxv);
}

Eigen::Matrix<double, 9, 1> FadingVelocity::cruiseStep(double seconds, const Eigen::Matrix3d& R,
                                                       const Eigen::Vector3d& cruise) const {
    const Step along = step(seconds), side = across().step(seconds);
    const double T = std::max(0.0, seconds);
    Eigen::Matrix<double, 9, 1> u = Eigen::Matrix<double, 9, 1>::Zero();
    u.head<3>() = R * Eigen::Vector3d(T - along.carry, T - side.carry, T - side.carry).cwiseProduct(cruise);
    u.segment<3>(3) = R * Eigen::Vector3d(1 - along.fade, 1 - side.fade, 1 - side.fade).cwiseProduct(cruise);
    return u;
}

}  // namespace lodestone::odometry
