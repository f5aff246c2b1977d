#pragma once

#include <lodestone/vision/GuidedMatcher.h>
#include <lodestone/vision/depth/DepthModel.h>

namespace lodestone::vision {

/** Why depth alignment gave no motion. */
enum class DepthAlignFailure { None, FewPoints, FewCorrespondences, Unobservable };
const char* toString(DepthAlignFailure f);

/** What aligning a frame's depth with the model gave. */
struct DepthAlignment {
    bool success{false};
    DepthAlignFailure failure{DepthAlignFailure::None};
    /** The frame's pose in the reference's optical frame: p_ref = T p_cur. */
    Eigen::Isometry3d T_ref_cur{Eigen::Isometry3d::Identity()};
    /** 6x6 covariance of a left perturbation exp(xi) T, xi = (rx, ry, rz, tx, ty, tz), as
     * RigidEstimate's: the inverse of the point-to-plane Hessian where the depth measured the
     * motion, `unobservedSigma` (scaled) along the directions it did not. */
    Eigen::Matrix<double, 6, 6> covariance{Eigen::Matrix<double, 6, 6>::Identity()};
    int observed{0};  ///< directions of the motion the depth measured (of 6)
    std::size_t points{0}, correspondences{0};
    double rmse{0};  ///< point-to-plane residual over the correspondences [m]
    /** With a measured motion: the joint solve's chi-square of the two against each other
     * (chi-square with `observed` dof where both covariances are honest); 0 without ... */
    double disagreement{0};
    /** ... past its 99 % quantile: one covariance was too tight, and `covariance` is scaled
     * by disagreement / observed to cover both. */
    bool disagreed{false};
    int iterations{0};
};

/** Point-to-plane ICP (Chen & Medioni; KinectFusion's and ElasticFusion's geometric term): the
 * frame's depth points, moved by the motion, against the model's nearest points along the
 * model's normals, weighted by both points' depth noise and a Huber kernel, solved by
 * Gauss-Newton from an initial motion (the wheels', the gyro's or constant velocity).
 *
 * A view can pin the motion only partly: a plain wall fixes the distance to it and two tilts, a
 * corridor everything but the move along it. Which directions the matched surfaces pin is read
 * from their normals (the geometry's eigenvalues against the normals' own noise, not the
 * Hessian's, which thousands of noisy normals fill in every direction): those are solved and
 * their covariance is the Hessian's there; the rest keep the initial motion and get
 * `unobservedSigma`, so a graph trusts only what the depth saw. */
class PointToPlaneIcp {
  public:
    struct Params {
        int iterations{20};
        double maxDistance{0.20};      ///< correspondence gate of the first iteration [m]
        double minDistance{0.04};      ///< the gate shrinks to this [m]
        double maxNormalAngle{0.52};   ///< normals further apart are not one surface [rad]
        double huber{2.0};             ///< Huber kernel's corner, in sigmas of the residual
        std::size_t minCorrespondences{300};
        double minOverlap{0.3};  ///< correspondences / frame points below this: no motion
        /** A direction counts as pinned when the share of the matched surface facing it (an
         * eigenvalue of the geometry's matrix, see the source) exceeds this many times what the
         * normals' own noise gives a plane (chi-square, 1 dof, 99.7 %)... */
        double normalNoiseChi2{9.0};
        double minStructure{1e-3};  ///< ...and this (a consistent tilt of about 2 deg)
        int minObserved{5};  ///< fewer measured directions: no motion (5: a corridor passes, a wall not)
        /** The sigma reported along a direction not pinned [m; for a rotation, metres at the
         * matched points' spread]. */
        double unobservedSigma{1.0};
    };

    PointToPlaneIcp() = default;
    explicit PointToPlaneIcp(const Params& params) : params_(params) {}

    /** Aligns `current` (its own optical frame) with `model` (the reference's), starting from
     * `initial`. With a `measured` motion (the features' alignment of the same two frames, its
     * covariance), the two are solved as one: the depth's information where it pins the
     * motion and the measurement's everywhere; every direction is then known, and
     * `minObserved` does not apply. */
    DepthAlignment align(const DepthModel& model, const DepthCloud& current,
                         const Eigen::Isometry3d& initial,
                         const MotionPrior* measured = nullptr) const;
    const Params& params() const { return params_; }

  private:
    Params params_;
};

}  // namespace lodestone::vision
