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

/** The planar error of z against a^-1 b (nodes as x, y, yaw), in z's frame. */
template <typename T, typename Z>
Eigen::Matrix<T, 3, 1> planarError(const T* a, const T* b, const Z& zx, const Z& zy,
                                   const Z& zyaw) {
    using std::cos;
    using std::sin;
    const T ca = cos(a[2]), sa = sin(a[2]);
    const T dx = b[0] - a[0], dy = b[1] - a[1];
    // Predicted motion in a's frame, then its difference to z in z's frame.
    const T px = ca * dx + sa * dy - T(zx), py = -sa * dx + ca * dy - T(zy);
    const Z cz = cos(zyaw), sz = sin(zyaw);
    Eigen::Matrix<T, 3, 1> e;
    e << T(cz) * px + T(sz) * py, T(-sz) * px + T(cz) * py, wrapAngle(b[2] - a[2] - T(zyaw));
    return e;
}

/** Nodes as (x, y, yaw). */
struct PlanarRelativePoseCost {
    PlanarRelativePoseCost(const Eigen::Vector3d& z, const Eigen::Matrix3d& sqrtInfo)
        : z_(z), sqrt_info_(sqrtInfo) {}

    template <typename T>
    bool operator()(const T* a, const T* b, T* residual) const {
        Eigen::Map<Eigen::Matrix<T, 3, 1>> out(residual);
        out = sqrt_info_.cast<T>() * planarError(a, b, z_.x(), z_.y(), z_.z());
        return true;
    }

  private:
    Eigen::Vector3d z_;
    Eigen::Matrix3d sqrt_info_;
};

/** An odometry edge corrected by the wheels' scale errors s (a third block, 2 values): the
 * measurement z + D s, D its (x, y, yaw) by (left, right) Jacobian (WheelScale). */
struct ScaledPlanarRelativePoseCost {
    ScaledPlanarRelativePoseCost(const Eigen::Vector3d& z, const Eigen::Matrix<double, 3, 2>& D,
                                 const Eigen::Matrix3d& sqrtInfo)
        : z_(z), d_(D), sqrt_info_(sqrtInfo) {}

    template <typename T>
    bool operator()(const T* a, const T* b, const T* scale, T* residual) const {
        const Eigen::Matrix<T, 3, 1> z =
            z_.cast<T>() + d_.cast<T>() * Eigen::Map<const Eigen::Matrix<T, 2, 1>>(scale);
        Eigen::Map<Eigen::Matrix<T, 3, 1>> out(residual);
        out = sqrt_info_.cast<T>() * planarError(a, b, z.x(), z.y(), z.z());
        return true;
    }

  private:
    Eigen::Vector3d z_;
    Eigen::Matrix<double, 3, 2> d_;
    Eigen::Matrix3d sqrt_info_;
};

/** The SE(3) error of z (translation zt, rotation inverse zqInv) against a^-1 b: the
 * translation difference in z's frame, then twice the error quaternion's vector part. */
template <typename T>
Eigen::Matrix<T, 6, 1> se3Error(const T* ta, const T* qa, const T* tb, const T* qb,
                                const Eigen::Matrix<T, 3, 1>& zt,
                                const Eigen::Quaternion<T>& zInv) {
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> pa(ta), pb(tb);
    const Eigen::Map<const Eigen::Quaternion<T>> rotA(qa), rotB(qb);
    const Eigen::Quaternion<T> aInv = rotA.conjugate();
    const Eigen::Matrix<T, 3, 1> pab = aInv * (pb - pa);
    Eigen::Quaternion<T> dq = zInv * (aInv * rotB);
    // q and -q are one rotation: take the short way.
    if (dq.w() < T(0)) dq.coeffs() = -dq.coeffs();
    Eigen::Matrix<T, 6, 1> e;
    e.template head<3>() = zInv * (pab - zt);
    e.template tail<3>() = T(2) * dq.vec();
    return e;
}

/** Nodes as translation (3) + unit quaternion (Eigen order x, y, z, w). The rotation error is
 * twice the vector part of the error quaternion (its rotation vector for small errors), ordered
 * about x, y, z. */
struct Se3RelativePoseCost {
    Se3RelativePoseCost(const Eigen::Vector3d& zt, const Eigen::Quaterniond& zq,
                        const Eigen::Matrix<double, 6, 6>& sqrtInfo)
        : zt_(zt), zq_inv_(zq.conjugate()), sqrt_info_(sqrtInfo) {}

    template <typename T>
    bool operator()(const T* ta, const T* qa, const T* tb, const T* qb, T* residual) const {
        Eigen::Map<Eigen::Matrix<T, 6, 1>> out(residual);
        out = sqrt_info_.cast<T>() *
              se3Error(ta, qa, tb, qb, Eigen::Matrix<T, 3, 1>(zt_.cast<T>()),
                       Eigen::Quaternion<T>(zq_inv_.cast<T>()));
        return true;
    }

  private:
    Eigen::Vector3d zt_;
    Eigen::Quaterniond zq_inv_;
    Eigen::Matrix<double, 6, 6> sqrt_info_;
};

/** Se3RelativePoseCost's odometry edge corrected by the wheels' scale errors s: its planar
 * translation moved by the first two rows of D s, its rotation turned about the vertical by
 * the third (ScaledPlanarRelativePoseCost in SE(3)). */
struct ScaledSe3RelativePoseCost {
    ScaledSe3RelativePoseCost(const Eigen::Vector3d& zt, const Eigen::Quaterniond& zq,
                              const Eigen::Matrix<double, 3, 2>& D,
                              const Eigen::Matrix<double, 6, 6>& sqrtInfo)
        : zt_(zt), zq_inv_(zq.conjugate()), d_(D), sqrt_info_(sqrtInfo) {}

    template <typename T>
    bool operator()(const T* ta, const T* qa, const T* tb, const T* qb, const T* scale,
                    T* residual) const {
        using std::cos;
        using std::sin;
        const Eigen::Matrix<T, 3, 1> dz =
            d_.cast<T>() * Eigen::Map<const Eigen::Matrix<T, 2, 1>>(scale);
        Eigen::Matrix<T, 3, 1> zt = zt_.cast<T>();
        zt.x() += dz.x();
        zt.y() += dz.y();
        // (Rz(d) zq)^-1 = zq^-1 Rz(-d)
        const T half = T(0.5) * dz.z();
        const Eigen::Quaternion<T> turnBack(cos(half), T(0), T(0), -sin(half));
        const Eigen::Quaternion<T> zInv = Eigen::Quaternion<T>(zq_inv_.cast<T>()) * turnBack;
        Eigen::Map<Eigen::Matrix<T, 6, 1>> out(residual);
        out = sqrt_info_.cast<T>() * se3Error(ta, qa, tb, qb, zt, zInv);
        return true;
    }

  private:
    Eigen::Vector3d zt_;
    Eigen::Quaterniond zq_inv_;
    Eigen::Matrix<double, 3, 2> d_;
    Eigen::Matrix<double, 6, 6> sqrt_info_;
};

/** The wheels' scale errors' prior: each scale over its sigma. */
struct WheelScalePriorCost {
    explicit WheelScalePriorCost(double sigma) : inv_sigma_(1 / sigma) {}

    template <typename T>
    bool operator()(const T* scale, T* residual) const {
        residual[0] = T(inv_sigma_) * scale[0];
        residual[1] = T(inv_sigma_) * scale[1];
        return true;
    }

  private:
    double inv_sigma_;
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

/** A node's height along the map's up against the level mapHeight marks (the floor, or the
 * carrier's common height on one floor) and its measured height above it: the residual
 * u_map . t - level - above, whitened by its sigma. */
struct HeightPriorCost {
    HeightPriorCost(double sigma, double above = 0) : inv_sigma_(1 / sigma), above_(above) {}

    template <typename T>
    bool operator()(const T* t, const T* mapUp, const T* height, T* residual) const {
        residual[0] = T(inv_sigma_) *
                      (mapUp[0] * t[0] + mapUp[1] * t[1] + mapUp[2] * t[2] - height[0] - T(above_));
        return true;
    }

  private:
    double inv_sigma_;
    double above_;
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
