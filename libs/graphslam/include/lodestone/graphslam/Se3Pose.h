#pragma once

#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>
#include <mrpt/poses/CPose3DPDFGaussianInf.h>

#include <Eigen/Geometry>

namespace lodestone::graphslam {

/** MRPT's 3-D pose as an Eigen isometry, and back. */
Eigen::Isometry3d isometryOf(const mrpt::poses::CPose3D& p);
mrpt::poses::CPose3D poseOf3D(const Eigen::Isometry3d& T);

/** A 6 x 6 covariance of a small right perturbation ordered (rotation w, translation v) - what
 * the vision library's RANSAC and VO report - in MRPT's order x, y, z, yaw, pitch, roll (yaw
 * about z = w_z, pitch = w_y, roll = w_x: first order). */
mrpt::math::CMatrixDouble66 mrptCovarianceOf(const Eigen::Matrix<double, 6, 6>& twistCovariance);

/** A visual closure's relative pose `T` with its twist covariance `cov` (as mrptCovarianceOf
 * takes it) as a graph constraint, each position variance floored by minSigmaXY^2 and each
 * angle's by minSigmaYaw^2 added: what a closer claims is never sharper than that. */
mrpt::poses::CPose3DPDFGaussianInf closureConstraint(const Eigen::Isometry3d& T,
                                                     const Eigen::Matrix<double, 6, 6>& cov,
                                                     double minSigmaXY, double minSigmaYaw);

/** How far apart two independent estimates of one pose are: the squared Mahalanobis distance
 * of their means' difference in MRPT's (x, y, z, yaw, pitch, roll), angles wrapped, under the
 * sum of their covariances (first order: for a gate, not for a fit). (MRPT's
 * CPose3DPDFGaussian::mahalanobisDistanceTo differences the angles unwrapped: headings of 179
 * and -179 deg, each 1 deg sure, come out 253 sigma apart instead of 1.4.) */
double squaredMahalanobis(const mrpt::poses::CPose3DPDFGaussian& a,
                          const mrpt::poses::CPose3DPDFGaussian& b);

/** A relative pose given that its rise (z, the first frame's up) is about zero to `sigma`
 * (a carrier's height over a step: a hand, a robot on its floor) - the pose's z conditioned on
 * N(0, sigma^2), its other components moving with it by their correlations: nothing where the
 * rise was measured far better than sigma, a bound where it was not. sigma 0: unchanged.
 * `moveRotation` false: only the translation moves, the rotation and its covariance stay and
 * the cross terms go (for an edge that drops them: VO's are its least sure part). */
mrpt::poses::CPose3DPDFGaussian heightHeld(const mrpt::poses::CPose3DPDFGaussian& pdf, double sigma,
                                           bool moveRotation = true);

/** A relative pose whose translation is also measured as `m` with covariance `M` (both in the
 * pose's first frame) - a motion model's guess of it: a Kalman update of the translation, the
 * other components moving with it by their correlations (`moveRotation` as heightHeld's).
 * Nothing changes where the pose's translation is known far better than `M`. */
mrpt::poses::CPose3DPDFGaussian translationHeld(const mrpt::poses::CPose3DPDFGaussian& pdf,
                                                const Eigen::Vector3d& m, const Eigen::Matrix3d& M,
                                                bool moveRotation = true);

}  // namespace lodestone::graphslam
