#pragma once

#include <lodestone/vision/BinaryWordIndex.h>
#include <lodestone/vision/FeatureSubmap.h>

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

namespace lodestone::vision {

/** The closed submaps and the two ways to find candidates among them, both sublinear in their
 * number: a KD-tree over submap centres (where the map says they are; refreshed when the caller
 * moves them, e.g. after an optimization) and an appearance index over their descriptors
 * (BinaryWordIndex), so a revisit is found even when odometry has drifted far. */
class SubmapCatalog {
  public:
    struct Candidate {
        std::size_t submap;
        double distance;  ///< [m] from the query position to the centre (inf: not searched)
        int votes;        ///< appearance votes (0: found by position only)
    };

    explicit SubmapCatalog(BinaryWordIndex::Params words = {});
    ~SubmapCatalog();

    /** Adds a closed submap with its centre in the map frame; returns its index. Its most
     * often seen descriptors go into the appearance index. */
    std::size_t add(std::shared_ptr<const FeatureSubmap> submap, const Eigen::Vector3d& centre);
    /** Moves submap `i`'s centre; the position index is rebuilt at the next query. */
    void setCentre(std::size_t i, const Eigen::Vector3d& centre);

    /** Up to `maxNear` submaps whose centre is within `radius` of `position` (nearest first)
     * and up to `maxSimilar` with at least `minVotes` appearance votes for `descriptors` (most
     * first), without repeats; submaps for which `eligible` says false are skipped. */
    std::vector<Candidate> candidates(const Eigen::Vector3d& position, double radius,
                                      const cv::Mat& descriptors, std::size_t maxNear,
                                      std::size_t maxSimilar, int minVotes,
                                      const std::function<bool(std::size_t)>& eligible) const;

    std::size_t size() const { return submaps_.size(); }
    const FeatureSubmap& at(std::size_t i) const { return *submaps_.at(i); }
    const Eigen::Vector3d& centre(std::size_t i) const { return centres_.at(i); }

  private:
    void rebuildTree() const;

    std::vector<std::shared_ptr<const FeatureSubmap>> submaps_;
    std::vector<Eigen::Vector3d> centres_;
    BinaryWordIndex words_;
    struct Tree;
    mutable std::unique_ptr<Tree> tree_;  // rebuilt lazily
    mutable bool tree_stale_{true};
};

}  // namespace lodestone::vision
