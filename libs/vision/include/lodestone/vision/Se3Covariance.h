#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace lodestone::vision {

/** The adjoint of a rigid motion A on twists ordered (w, v) (rotation first, as RigidEstimate's
 * covariance): a left perturbation exp(xi) of a motion seen in A's source frame is
 * exp(Ad(A) xi) in A's destination frame. */
Eigen::Matrix<double, 6, 6> adjoint(const Eigen::Isometry3d& A);

/** A covariance of a left perturbation of T (exp(xi) T) as one of a right perturbation
 * (T exp(xi)): Ad(T^-1) C Ad(T^-1)^T. */
Eigen::Matrix<double, 6, 6> leftToRightCovariance(const Eigen::Isometry3d& T,
                                                  const Eigen::Matrix<double, 6, 6>& left);

}  // namespace lodestone::vision
