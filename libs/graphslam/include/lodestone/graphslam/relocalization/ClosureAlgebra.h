#pragma once

#include <lodestone/graphslam/relocalization/ClosureSpace.h>

#include <vector>

namespace lodestone::graphslam::relocalization {

/** The pieces the relocalizer needs, in the graph's pose space S (PlanarSpace: x, y, yaw;
 * SpatialSpace: SE(3)): a closure's residual, the rigid move of a group it implies, and
 * whether two closures tell the same story (pairwise consistency, as in PCM: Mangelson et al.,
 * ICRA 2018). Jacobians are numerical (central differences) in S's perturbation chart. */

/** One closure seen from the relocalizer: anchored end a, moving end u, and what is claimed. */
template <class S>
struct HypothesisT {
    typename S::Pose a, u;  ///< current graph poses of the two ends
    typename S::Pose z;     ///< the closure's relative pose (from -> to)
    typename S::Matrix cov; ///< its covariance (S's chart)
    bool uIsTo{true};
};

/** r = z^-1 (+) (from^-1 (+) to): zero when the two poses agree with the closure. */
template <class S>
typename S::Vector closureResidual(const typename S::Pose& from, const typename S::Pose& to,
                                   const typename S::Pose& z);

/** A closure between a node `a` of one group and a node `u` of a group to be moved: the rigid
 * transform T of the moved group that makes it hold exactly (T (+) u_pose satisfies it).
 * `uIsTo`: u is the closure's `to` end (else its `from`). */
template <class S>
typename S::Pose impliedTransform(const HypothesisT<S>& h);

/** Squared Mahalanobis distance between what two closures say of the moved group: the map
 * poses they give u_i and u_j, related as the moved group's own odometry relates them.
 * `odometryCov`: covariance of u_i^-1 (+) u_j (the moved group's relative pose between them);
 * `mapCov`: of a_i^-1 (+) a_j, the anchored group's own. First-order propagation with numerical
 * Jacobians of the closures' parameters. S::kDof degrees of freedom. */
template <class S>
double pairwiseChi2(const HypothesisT<S>& i, const HypothesisT<S>& j,
                    const typename S::Matrix& odometryCov, const typename S::Matrix& mapCov);

/** The move T of a group that best satisfies the given closures (Gauss-Newton, weighted by
 * their information), starting from `start`; `covariance`, when given, gets that of T (S's
 * perturbation chart: the inverse of the normal matrix). */
template <class S>
typename S::Pose fitTransform(const std::vector<HypothesisT<S>>& hs, const typename S::Pose& start,
                              typename S::Matrix* covariance = nullptr);

/** Covariance of T (+) u given T's, in T (+) u's own frame: how well a move pins down a pose of
 * the moved group (its position block's eigenvalues and its rotation block do not depend on
 * the frame). */
template <class S>
typename S::Matrix movedPoseCovariance(const typename S::Pose& T, const typename S::Matrix& covT,
                                       const typename S::Pose& u);

/** Squared Mahalanobis residual of hypothesis h after its u end is moved by T. */
template <class S>
double chi2After(const HypothesisT<S>& h, const typename S::Pose& T);

}  // namespace lodestone::graphslam::relocalization
