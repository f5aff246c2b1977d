#pragma once

#include <lodestone/vision/depth/DepthCloud.h>

#include <cstdint>
#include <deque>
#include <memory>

namespace lodestone::vision {

/** The local model depth alignment aligns a frame with: the depth clouds of the last few
 * keyframes, all in the optical frame of the newest (the reference), searched by nearest
 * neighbour. A frame turning away from the reference still meets the surfaces the keyframes
 * before it saw. */
class DepthModel {
  public:
    explicit DepthModel(int keyframes = 3);
    ~DepthModel();
    DepthModel(DepthModel&&) noexcept;
    DepthModel& operator=(DepthModel&&) noexcept;

    /** Forgets every keyframe (a new segment). */
    void clear();
    /** A new reference keyframe, its cloud in its own optical frame; `T_new_old` is the previous
     * reference's pose in the new one's frame (the inverse of the motion that made the new one).
     * The oldest keyframe beyond `keyframes` is dropped. A motion that did not pin every
     * direction (`pinned` false: depth alignment's loose axes) leaves the older keyframes'
     * place unknown, and they are dropped: a model misplaced by a guess biases what the next
     * alignment pins. */
    void addReference(DepthCloud cloud, const Eigen::Isometry3d& T_new_old, bool pinned = true);

    bool empty() const { return keyframes_.empty(); }
    int keyframeCount() const { return static_cast<int>(keyframes_.size()); }
    /** Points over all keyframes. */
    std::size_t size() const;

    struct Nearest {
        Eigen::Vector3f point, normal;
        float sigma{0};
        float normalVariance{0};
        float distance2{0};
        std::int64_t index{-1};  ///< the point's index in the model, until the model changes
    };
    /** The model's point nearest `p` (reference frame) within sqrt(maxDistance2), if any.
     * `near`, a model point's index (a previous search's answer for a point that has hardly
     * moved since, as between ICP iterations), bounds the search by its distance: the nearest
     * point lies no farther. The point found is the same; fewer of the tree's cells are
     * searched. */
    bool nearest(const Eigen::Vector3f& p, float maxDistance2, Nearest& out,
                 std::int64_t near = -1) const;

  private:
    struct Keyframe {
        DepthCloud cloud;           ///< in its own optical frame
        Eigen::Isometry3d T_ref_kf;  ///< its pose in the reference's frame
    };
    void build() const;

    int max_keyframes_;
    std::deque<Keyframe> keyframes_;
    struct Index;
    mutable std::unique_ptr<Index> index_;  // built on first use after a change
};

}  // namespace lodestone::vision
