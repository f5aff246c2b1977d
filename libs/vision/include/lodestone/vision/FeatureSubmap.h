#pragma once

#include <lodestone/vision/OrbFeatures.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

namespace lodestone::vision {

/** The 3D ORB features of consecutive keyframes accumulated in the robot frame of the submap's
 * first node, paper 000 eq. (1): M = sum_i X_0^-1 X_i T_C^R p_i, descriptors carried along. In a
 * feature-poor stretch one keyframe has too few features to match; a submap gathers enough.
 * A feature seen again (within `mergeRadius`, descriptor within `mergeMaxDistance`) is merged into
 * the one it repeats (position averaged over its sightings), not duplicated. */
class FeatureSubmap {
  public:
    struct Params {
        double mergeRadius{0.03};   ///< [m]
        int mergeMaxDistance{40};   ///< [bits] Hamming
    };
    /** One keyframe of the submap. */
    struct Member {
        std::int64_t node{0};
        Eigen::Isometry3d T_submap_robot{Eigen::Isometry3d::Identity()};  ///< X_0^-1 X_i (robot)
        Eigen::Isometry3d T_robot_camera{Eigen::Isometry3d::Identity()};  ///< T_C^R
        std::shared_ptr<const FrameFeatures> features;                    ///< optical frame
    };

    FeatureSubmap();
    explicit FeatureSubmap(Params params);

    /** Adds keyframe `node` at `T_submap_robot` (X_0^-1 X_i; identity for the first) with its
     * features in the optical frame and the camera's pose on the robot. Returns how many of its
     * features were merged into existing ones. */
    std::size_t add(std::int64_t node, const Eigen::Isometry3d& T_submap_robot,
                    const Eigen::Isometry3d& T_robot_camera,
                    std::shared_ptr<const FrameFeatures> features);

    std::size_t size() const { return points_.size(); }
    bool empty() const { return members_.empty(); }
    /** Submap-frame points, column i for descriptor row i. */
    Eigen::Matrix3Xd points() const;
    const cv::Mat& descriptors() const { return descriptors_; }
    /** How many keyframes saw point i. */
    const std::vector<int>& sightings() const { return sightings_; }
    /** Point indices, most often seen first (ties in insertion order); cached until the next
     * add(). */
    const std::vector<int>& strongestFirst() const;
    const std::vector<Member>& members() const { return members_; }
    /** The mean of its keyframes' robot positions, in the submap frame: where it "is". */
    Eigen::Vector3d centre() const;
    std::int64_t firstNode() const { return members_.front().node; }
    std::int64_t lastNode() const { return members_.back().node; }
    /** The member whose robot pose is nearest to `pose` (position, plus 0.5 m per radian of
     * heading difference: a keyframe facing the same way sees the same things). */
    const Member& nearestMember(const Eigen::Isometry3d& pose) const;

  private:
    Params params_;
    std::vector<Eigen::Vector3f> points_;
    std::vector<int> sightings_;
    cv::Mat descriptors_;
    std::vector<Member> members_;
    mutable std::vector<int> strongest_;  // cache of strongestFirst()
};

}  // namespace lodestone::vision
