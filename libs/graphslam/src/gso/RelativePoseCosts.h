#pragma once
// Relative-pose errors of one pose-graph edge, for Ceres' automatic differentiation.
// Both give the error of the measurement z against the predicted motion a^-1 b as z^-1 (a^-1 b)
// in the local coordinates of z, whitened by the square root of the edge's information matrix.

#include <ceres/jet.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>

namespace lodestone::graphslam::detail {

/** An angle wrapped to [-pi, pi); floor() has zero derivative, so Jets pass through. */
template <typename T>
T wrapAngle(const T& a) {
    using std::floor;
    const T twoPi = T(2 * M_PI);
    return a - twoPi * floor((a + T(M_PI)) / twoPi);
}

/** Nodes as (x, y, yaw). */
struct PlanarRelativePoseCost {
    PlanarRelativePoseCost(const Eigen::Vector3d& z, const Eigen::Matrix3d& sqrtInfo)
        : z_(z), sqrt_info_(sqrtInfo) {}

    template <typename T>
    bool operator()(const T* a, const T* b, T* residual) const {
        using std::cos;
        using std::sin;
        const T ca = cos(a[2]), sa = sin(a[2]);
        const T dx = b[0] - a[0], dy = b[1] - a[1];
        // Predicted motion in a's frame, then its difference to z in z's frame.
        const T px = ca * dx + sa * dy - T(z_.x()), py = -sa * dx + ca * dy - T(z_.y());
        const double cz = std::cos(z_.z()), sz = std::sin(z_.z());
        Eigen::Matrix<T, 3, 1> e;
        e << T(cz) * px + T(sz) * py, T(-sz) * px + T(cz) * py, wrapAngle(b[2] - a[2] - T(z_.z()));
        Eigen::Map<Eigen::Matrix<T, 3, 1>> out(residual);
        out = sqrt_info_.cast<T>() * e;
        return true;
    }

  private:
    Eigen::Vector3d z_;
    Eigen::Matrix3d sqrt_info_;
};

/** Nodes as translation (3) + unit quaternion (Eigen order x, y, z, w). The rotation error is
 * twice the vector part of the error quaternion (its rotation vector for small errors), ordered
 * about x, y, z. */
struct Se3RelativePoseCost {
    Se3RelativePoseCost(const Eigen::Vector3d& zt, const Eigen::Quaterniond& zq,
                        const Eigen::Matrix<double, 6, 6>& sqrtInfo)
        : zt_(zt), zq_inv_(zq.conjugate()), sqrt_info_(sqrtInfo) {}

    template <typename T>
    bool operator()(const T* ta, const T* qa, const T* tb, const T* qb, T* residual) const {
        const Eigen::Map<const Eigen::Matrix<T, 3, 1>> pa(ta), pb(tb);
        const Eigen::Map<const Eigen::Quaternion<T>> rotA(qa), rotB(qb);
        const Eigen::Quaternion<T> aInv = rotA.conjugate();
        const Eigen::Matrix<T, 3, 1> pab = aInv * (pb - pa);
        const Eigen::Quaternion<T> zInv = zq_inv_.cast<T>();
        Eigen::Quaternion<T> dq = zInv * (aInv * rotB);
        // q and -q are one rotation: take the short way.
        if (dq.w() < T(0)) dq.coeffs() = -dq.coeffs();
        Eigen::Matrix<T, 6, 1> e;
        e.template head<3>() = zInv * (pab - zt_.cast<T>());
        e.template tail<3>() = T(2) * dq.vec();
        Eigen::Map<Eigen::Matrix<T, 6, 1>> out(residual);
        out = sqrt_info_.cast<T>() * e;
        return true;
    }

  private:
    Eigen::Vector3d zt_;
    Eigen::Quaterniond zq_inv_;
    Eigen::Matrix<double, 6, 6> sqrt_info_;
};

/** A node's measured up (in its own frame) against the map's up turned into it: the residual
 * R^T u_map - u_measured, whitened by its per-axis sigma (the part along u is second order). */
struct AttitudePriorCost {
    AttitudePriorCost(const Eigen::Vector3d& up, double sigma) : up_(up), inv_sigma_(1 / sigma) {}

    template <typename T>
    bool operator()(const T* q, const T* mapUp, T* residual) const {
        const Eigen::Map<const Eigen::Quaternion<T>> rot(q);
        const Eigen::Map<const Eigen::Matrix<T, 3, 1>> u(mapUp);
        Eigen::Map<Eigen::Matrix<T, 3, 1>> out(residual);
        out = T(inv_sigma_) * (rot.conjugate() * u - up_.cast<T>());
        return true;
    }

  private:
    Eigen::Vector3d up_;
    double inv_sigma_;
};

/** S with S^T S = info, for an information matrix that may be only semi-definite (a weak or
 * partly unobserved edge): eigenvalues below zero are treated as zero. */
template <int N>
Eigen::Matrix<double, N, N> informationSqrt(const Eigen::Matrix<double, N, N>& info) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> es(
        0.5 * (info + info.transpose()));
    const Eigen::Matrix<double, N, 1> root = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
    return root.asDiagonal() * es.eigenvectors().transpose();
}

}  // namespace lodestone::graphslam::detail
