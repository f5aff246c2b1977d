#pragma once

#include <lodestone/graphslam/PoseGraph.h>
#include <mrpt/poses/CPose2D.h>

#include <Eigen/Core>

namespace lodestone::graphslam::relocalization {

/** SE(2) pieces the relocalizer needs: a closure's residual, the rigid move of a segment it
 * implies, and whether two closures tell the same story (pairwise consistency, as in PCM:
 * Mangelson et al., ICRA 2018). Poses are the planar part (x, y, yaw) of the graph's. */

using Pose2 = mrpt::poses::CPose2D;
using Vector3 = Eigen::Vector3d;
using Matrix3 = Eigen::Matrix3d;

Pose2 planar(const mrpt::poses::CPose3D& p);
/** x, y, yaw with yaw wrapped to (-pi, pi]. */
Vector3 vectorOf(const Pose2& p);
Pose2 poseOf(const Vector3& v);

/** The x, y, yaw block of a constraint's information (MRPT order x y z yaw pitch roll). */
Matrix3 planarInformation(const Constraint& c);
/** Its inverse, the closure's claimed covariance on (x, y, yaw) of the relative pose. */
Matrix3 planarCovariance(const Constraint& c);

/** r = z^-1 (+) (from^-1 (+) to): zero when the two poses agree with the closure. */
Vector3 closureResidual(const Pose2& from, const Pose2& to, const Pose2& z);

/** A closure between a node `a` of one group and a node `u` of a group to be moved: the rigid
 * transform T of the moved group that makes it hold exactly (T (+) u_pose satisfies it).
 * `uIsTo`: u is the closure's `to` end (else its `from`). */
Pose2 impliedTransform(const Pose2& a, const Pose2& u, const Pose2& z, bool uIsTo);

/** One closure seen from the relocalizer: anchored end a, moving end u, and what is claimed. */
struct Hypothesis {
    Pose2 a, u;     ///< current graph poses of the two ends
    Pose2 z;        ///< the closure's relative pose (from -> to)
    Matrix3 cov;    ///< its covariance on z's x, y, yaw
    bool uIsTo{true};
};

/** Squared Mahalanobis distance between what two closures say of the moved group: the map
 * poses they give u_i and u_j, related as the moved group's own odometry relates them.
 * `odometryCov`: covariance of u_i^-1 (+) u_j (the moved group's relative pose between them);
 * `mapCov`: of a_i^-1 (+) a_j, the anchored group's own. First-order propagation with numerical
 * Jacobians of the closures' parameters. 3 degrees of freedom. */
double pairwiseChi2(const Hypothesis& i, const Hypothesis& j, const Matrix3& odometryCov,
                    const Matrix3& mapCov);

/** The move T of a group that best satisfies the given closures (Gauss-Newton on SE(2),
 * weighted by their information), starting from `start`; `covariance`, when given, gets that
 * of T's x, y, yaw (the inverse of the normal matrix). */
Pose2 fitTransform(const std::vector<Hypothesis>& hs, const Pose2& start,
                   Matrix3* covariance = nullptr);
/** Covariance of T (+) u given T's: how well a move pins down a pose of the moved group. */
Matrix3 movedPoseCovariance(const Pose2& T, const Matrix3& covT, const Pose2& u);
/** Squared Mahalanobis residual of hypothesis h after its u end is moved by T. */
double chi2After(const Hypothesis& h, const Pose2& T);

}  // namespace lodestone::graphslam::relocalization
