#pragma once

#include <lodestone/vision/DescriptorMatcher.h>
#include <lodestone/vision/OrbFeatures.h>
#include <lodestone/vision/RigidRansac.h>

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
};

/** What SubmapMatcher's second phase and ProximityERD do with a pair of keyframes: fewer
 * than `ransac`'s minimum inliers in matches is no alignment. */
KeyframePairAlignment alignKeyframePair(const DescriptorMatcher& matcher, const RigidRansac& ransac,
                                        const FrameFeatures& reference,
                                        const Eigen::Isometry3d& T_robot_referenceCamera,
                                        const FrameFeatures& query,
                                        const Eigen::Isometry3d& T_robot_queryCamera,
                                        std::uint64_t seed);

}  // namespace lodestone::vision
