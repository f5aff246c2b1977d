#pragma once

#include <lodestone/vision/GuidedMatcher.h>

#include <Eigen/Core>

namespace lodestone::vision {

/** A motion the camera measured (`T_ref_cur` and the covariance of a left perturbation
 * exp(xi) T, xi = (rotation, translation): RigidEstimate's) joined with an independent
 * measurement of its rotation - a gyro's `R` since the reference, `sigma` [rad] per axis: one
 * Kalman update on the rotation. Where the camera's rotation is loose, its translation moves
 * with it as their correlation says: features far ahead in a narrow band of the view (a
 * corridor's floor beyond 3 m) leave a pitch and a shift along the view that trade off, and
 * the gyro's pitch then pins both.
 *
 * With `freeAxis` (non-zero, in the same frame as the rotation vector of T), the turn about
 * that axis is left out of the measurement: only the rotation about the axes across it joins. */
MotionPrior joinRotation(const MotionPrior& camera, const Eigen::Matrix3d& R, double sigma,
                         const Eigen::Vector3d& freeAxis = Eigen::Vector3d::Zero());

}  // namespace lodestone::vision
