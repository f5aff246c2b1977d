#include <lodestone/vision/SubmapCatalog.h>

#include <nanoflann.hpp>

#include <algorithm>
#include <limits>
#include <numeric>

namespace lodestone::vision {

namespace {
struct CentreCloud {
    const std::vector<Eigen::Vector3d>* pts;
    std::size_t kdtree_get_point_count() const { return pts->size(); }
    double kdtree_get_pt(std::size_t i, std::size_t d) const { return (*pts)[i][static_cast<int>(d)]; }
    template <class BBox>
    bool kdtree_get_bbox(BBox&) const {
        return false;
    }
};
using CentreTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, CentreCloud>, CentreCloud, 3>;
}  // namespace

struct SubmapCatalog::Tree {
    CentreCloud cloud;
    CentreTree index;
    explicit Tree(const std::vector<Eigen::Vector3d>* pts)
        : cloud{pts}, index(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
        index.buildIndex();
    }
};

SubmapCatalog::SubmapCatalog(BinaryWordIndex::Params words) : words_(words) {}
SubmapCatalog::~SubmapCatalog() = default;

std::size_t SubmapCatalog::add(std::shared_ptr<const FeatureSubmap> submap,
                               const Eigen::Vector3d& centre) {
    const std::size_t i = submaps_.size();
    // Index the features seen most often first: they are the stable ones.
    const std::vector<int>& order = submap->strongestFirst();
    cv::Mat sorted(static_cast<int>(order.size()), 32, CV_8U);
    for (std::size_t k = 0; k < order.size(); ++k) {
        submap->descriptors().row(order[k]).copyTo(sorted.row(static_cast<int>(k)));
    }
    words_.add(static_cast<std::uint32_t>(i), sorted);
    submaps_.push_back(std::move(submap));
    centres_.push_back(centre);
    tree_stale_ = true;
    return i;
}

void SubmapCatalog::setCentre(std::size_t i, const Eigen::Vector3d& centre) {
    centres_.at(i) = centre;
    tree_stale_ = true;
}

void SubmapCatalog::rebuildTree() const {
    tree_ = std::make_unique<Tree>(&centres_);
    tree_stale_ = false;
}

std::vector<SubmapCatalog::Candidate> SubmapCatalog::candidates(
    const Eigen::Vector3d& position, double radius, const cv::Mat& descriptors,
    std::size_t maxNear, std::size_t maxSimilar, int minVotes,
    const std::function<bool(std::size_t)>& eligible) const {
    std::vector<Candidate> out;
    if (submaps_.empty()) return out;
    const auto listed = [&](std::size_t s) {
        return std::any_of(out.begin(), out.end(), [&](const Candidate& c) { return c.submap == s; });
    };
    // By appearance first: it finds the revisit whatever the drift.
    if (maxSimilar > 0 && !descriptors.empty()) {
        // Ask for more than needed: some may be ineligible (too recent).
        for (const auto& [place, votes] : words_.query(descriptors, 4 * maxSimilar + 8)) {
            if (out.size() >= maxSimilar) break;
            if (votes < minVotes || !eligible(place)) continue;
            out.push_back({place, (centres_[place] - position).norm(), votes});
        }
    }
    if (maxNear > 0 && radius > 0) {
        if (tree_stale_ || !tree_) rebuildTree();
        std::vector<std::pair<std::uint32_t, double>> near;
        tree_->index.radiusSearch(position.data(), radius * radius, near, nanoflann::SearchParams(32, 0, true));
        std::size_t added = 0;
        for (const auto& [idx, d2] : near) {
            if (added >= maxNear) break;
            if (!eligible(idx) || listed(idx)) continue;
            out.push_back({idx, std::sqrt(d2), 0});
            ++added;
        }
    }
    return out;
}

}  // namespace lodestone::vision
