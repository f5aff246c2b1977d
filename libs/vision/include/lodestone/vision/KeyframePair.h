#pragma once

#include <lodestone/vision/DescriptorMatcher.h>
#include <lodestone/vision/OrbFeatures.h>
#include <lodestone/vision/RigidRansac.h>
#include <lodestone/vision/depth/PointToPlaneIcp.h>

#include <Eigen/Geometry>
#include <cstdint>

namespace lodestone::vision {

/** Two keyframes' features aligned node to node: their descriptors matched, the matched 3D
 * points (optical frames) aligned by RANSAC, the motion taken into the robots' frames. */
struct KeyframePairAlignment {
    bool success{false};
    std::size_t matches{0}, inliers{0};
    /** The `query` keyframe's robot pose in the `reference` keyframe's robot frame, and the
     * covariance of a right perturbation T exp(xi), xi = (rx, ry, rz, tx, ty, tz). */
    Eigen::Isometry3d referenceToQuery{Eigen::Isometry3d::Identity()};
    Eigen::Matrix<double, 6, 6> covariance{Eigen::Matrix<double, 6, 6>::Identity()};
    /** The same between the optical frames (p_reference = T p_query), the covariance of a left
     * perturbation as RigidEstimate's: what a depth alignment starts from. */
    Eigen::Isometry3d opticalReferenceToQuery{Eigen::Isometry3d::Identity()};
    Eigen::Matrix<double, 6, 6> opticalCovariance{Eigen::Matrix<double, 6, 6>::Identity()};
    /** joinKeyframeDepth: the depth solved with the features, and what it said. */
    bool depthJoined{false}, depthDisagreed{false};
    std::size_t depthCorrespondences{0};
};

/** What SubmapMatcher's second phase and ProximityERD do with a pair of keyframes: fewer
 * than `ransac`'s minimum inliers in matches is no alignment. */
KeyframePairAlignment alignKeyframePair(const DescriptorMatcher& matcher, const RigidRansac& ransac,
                                        const FrameFeatures& reference,
                                        const Eigen::Isometry3d& T_robot_referenceCamera,
                                        const FrameFeatures& query,
                                        const Eigen::Isometry3d& T_robot_queryCamera,
                                        std::uint64_t seed);

/** An alignment of features (`a`, successful) solved again with the two keyframes' depth, as
 * visual odometry's joined step: the query's depth cloud against the reference's (each in its
 * optical frame), point to plane, the features' motion and covariance a measurement in the
 * same Gauss-Newton (PointToPlaneIcp::align). Where the depth does not align `a` stays the
 * features' alone (depthJoined false). */
void joinKeyframeDepth(const PointToPlaneIcp& icp, const DepthCloud& reference,
                       const Eigen::Isometry3d& T_robot_referenceCamera, const DepthCloud& query,
                       const Eigen::Isometry3d& T_robot_queryCamera, KeyframePairAlignment& a);

}  // namespace lodestone::vision
