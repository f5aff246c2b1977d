#pragma once

#include <lodestone/vision/DescriptorMatcher.h>
#include <lodestone/vision/FeatureSubmap.h>
#include <lodestone/vision/RigidRansac.h>

#include <string>

namespace lodestone::vision {

/** Two-phase matching of a keyframe against a submap (paper 000 §2.1).
 *  Phase 1: the keyframe's ORB features (robot frame) against the submap's accumulated ones,
 *  RANSAC rigid transformation in 3D: where the keyframe's robot stands in the submap frame.
 *  Phase 2: the submap keyframe nearest to that pose; the two keyframes aligned again, optical
 *  frame to optical frame: the node-to-node constraint, with a covariance from the inlier
 *  residuals. If phase 2 fails (too few features in the nearest keyframe alone: the very case
 *  submaps are for) or disagrees with phase 1, phase 1's pose relative to that keyframe is used
 *  with its covariance inflated, when `phase1Fallback` is on and phase 1 has at least
 *  `fallbackMinInliers` inliers. Both RANSACs stop adaptively (99.9 % confidence). */
class SubmapMatcher {
  public:
    struct Params {
        DescriptorMatcher::Params matcher;
        RigidRansac::Params phase1;  ///< robot / submap frames: no depth-dependent terms
        RigidRansac::Params phase2;  ///< optical frames, as visual odometry
        std::size_t phase1MaxFeatures{1000};  ///< submap features matched, most seen first
        bool phase1Fallback{true};
        std::size_t fallbackMinInliers{40};  ///< phase-1 inliers a fallback needs
        double fallbackInflation{4.0};   ///< covariance factor of a phase-1 constraint
        double agreementDistance{0.3};   ///< [m] phase 2 must stay this close to phase 1 ...
        double agreementAngle{0.17};     ///< [rad] ... and this
        Params();
    };

    /** What one match attempt gave. */
    struct Result {
        bool success{false};
        std::string failure;  ///< why not, for reports
        std::size_t matches{0}, inliers{0};          ///< phase 1
        std::size_t phase2Matches{0}, phase2Inliers{0};
        bool usedPhase2{false};
        Eigen::Isometry3d submapToQuery{Eigen::Isometry3d::Identity()};  ///< phase 1 (robot)
        std::int64_t node{-1};  ///< the submap keyframe the constraint starts from
        /** The query keyframe's robot pose in `node`'s robot frame, and the covariance of a
         * right perturbation T exp(xi), xi = (rx, ry, rz, tx, ty, tz). */
        Eigen::Isometry3d nodeToQuery{Eigen::Isometry3d::Identity()};
        Eigen::Matrix<double, 6, 6> covariance{Eigen::Matrix<double, 6, 6>::Identity()};
        double phase1Ms{0}, phase2Ms{0};
    };

    SubmapMatcher();
    explicit SubmapMatcher(Params params);
    Result match(const FeatureSubmap& submap, const FrameFeatures& query,
                 const Eigen::Isometry3d& T_robot_queryCamera, std::uint64_t seed = 1) const;
    const Params& params() const { return params_; }

  private:
    Params params_;
    DescriptorMatcher matcher_;
    RigidRansac phase1_, phase2_;
};

}  // namespace lodestone::vision
