#include <lodestone/odometry/DepthTurn.h>
#include <lodestone/vision/So3.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include <algorithm>

namespace lodestone::odometry {

using vision::expSO3;
using vision::logSO3;
using vision::skew;

void DepthTurn::start(double t0, const Eigen::Vector3d& w0, const Eigen::Matrix3d& w0Covariance,
                      const Eigen::Vector3d& up) {
    t_ = t0;
    R_ = Rm_ = Eigen::Matrix3d::Identity();
    w_ = w0;
    up_ = up.normalized();
    P_.setZero();
    P_.block<3, 3>(3, 3) = w0Covariance;
}

void DepthTurn::predict(double t) {
    const double dt = std::max(0.0, t - t_);
    t_ = std::max(t_, t);
    if (dt == 0) return;
    const auto s = params_.rate.step(dt);
    // The mean: the rate fades, the rotation turns by what it carries (first order in the
    // error: the rotation's error grows by the rate's, the step's own turn of it neglected).
    R_ = R_ * expSO3(s.carry * w_);
    w_ *= s.fade;
    Matrix9d F, Q;
    s.matrices(F, Q);
    P_ = F * P_ * F.transpose() + Q;
    holdTilt(dt);
}

void DepthTurn::anchor() {
    Rm_ = R_;
    P_.block<3, 9>(6, 0) = P_.block<3, 9>(0, 0);
    P_.block<9, 3>(0, 6) = P_.block<9, 3>(0, 0);
}

bool DepthTurn::update(const Eigen::Matrix3d& measured, const Eigen::Matrix3d& covariance) {
    // R_m^T R with both perturbed on the right: Rhat exp(theta - Rhat^T theta_m), first order.
    const Eigen::Matrix3d predicted = Rm_.transpose() * R_;
    const Eigen::Vector3d y = logSO3(predicted.transpose() * measured);
    Eigen::Matrix<double, 3, 9> H = Eigen::Matrix<double, 3, 9>::Zero();
    H.leftCols<3>().setIdentity();
    H.rightCols<3>() = -predicted.transpose();
    const Eigen::Matrix3d S = H * P_ * H.transpose() + covariance;
    const Eigen::LDLT<Eigen::Matrix3d> Sl(S);
    if (!(y.dot(Sl.solve(y)) <= params_.gateChi2)) return false;
    const Eigen::Matrix<double, 9, 3> K = Sl.solve(H * P_).transpose();
    const Eigen::Matrix<double, 9, 1> dx = K * y;
    R_ = R_ * expSO3(dx.head<3>());
    w_ += dx.segment<3>(3);
    Rm_ = Rm_ * expSO3(dx.tail<3>());
    const Matrix9d IKH = Matrix9d::Identity() - K * H;
    P_ = IKH * P_ * IKH.transpose() + K * covariance * K.transpose();  // (Joseph: stays symmetric)
    return true;
}

void DepthTurn::holdTilt(double dt) {
    if (!(params_.tiltSigma > 0) || !(dt > 0)) return;
    // The start's up seen from now, R^T u, measured as u itself (the tilt unchanged), as one
    // independent sample of a bounded tilt per `tiltSeconds`: each frame's share
    // of it. Its Jacobian in the right perturbation is [R^T u]x, blind to the turn about up.
    const Eigen::Vector3d seen = R_.transpose() * up_;
    Eigen::Matrix<double, 3, 9> H = Eigen::Matrix<double, 3, 9>::Zero();
    H.leftCols<3>() = skew(seen);
    const double variance =
        params_.tiltSigma * params_.tiltSigma * std::max(1.0, params_.tiltSeconds / dt);
    const Eigen::Matrix3d S = H * P_ * H.transpose() + variance * Eigen::Matrix3d::Identity();
    const Eigen::Matrix<double, 9, 3> K = S.ldlt().solve(H * P_).transpose();
    const Eigen::Matrix<double, 9, 1> dx = K * (up_ - seen);
    R_ = R_ * expSO3(dx.head<3>());
    w_ += dx.segment<3>(3);
    Rm_ = Rm_ * expSO3(dx.tail<3>());
    const Matrix9d IKH = Matrix9d::Identity() - K * H;
    P_ = IKH * P_ * IKH.transpose() + variance * K * K.transpose();
}

}  // namespace lodestone::odometry
