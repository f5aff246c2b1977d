#include <lodestone/vision/depth/DepthModel.h>

#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lodestone::vision {

/** Every keyframe's cloud in the reference frame, and nanoflann's tree over it. */
struct DepthModel::Index {
    DepthCloud merged;
    std::size_t kdtree_get_point_count() const { return merged.size(); }
    float kdtree_get_pt(std::size_t i, std::size_t d) const {
        return merged.points(static_cast<Eigen::Index>(d), static_cast<Eigen::Index>(i));
    }
    template <class BBox>
    bool kdtree_get_bbox(BBox&) const {
        return false;
    }
    using Tree =
        nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Index>, Index, 3>;
    std::unique_ptr<Tree> tree;
};

namespace {
/** nanoflann's result set for the one nearest point no farther than a bound: subtrees beyond
 * the bound are never searched (the ICP's gate - most of the tree, for most points). The point
 * found is the one nanoflann's KNNResultSet(1) finds where it lies within the bound: the same
 * traversal, ties kept by the first met, pruned only where nothing within the bound lies. */
struct NearestWithin {
    explicit NearestWithin(float maxDistance2)
        : best(std::nextafter(maxDistance2, std::numeric_limits<float>::infinity())) {}
    float best;  // (the bound itself is within: a point exactly at it is found)
    std::size_t index{0};
    bool found{false};
    float worstDist() const { return best; }
    bool full() const { return found; }
    bool addPoint(float dist, std::size_t i) {
        if (dist < best) {
            best = dist;
            index = i;
            found = true;
        }
        return true;  // (search on: a nearer point may lie in another leaf)
    }
};
}  // namespace

DepthModel::DepthModel(int keyframes) : max_keyframes_(std::max(1, keyframes)) {}
DepthModel::~DepthModel() = default;
DepthModel::DepthModel(DepthModel&&) noexcept = default;
DepthModel& DepthModel::operator=(DepthModel&&) noexcept = default;

void DepthModel::clear() {
    keyframes_.clear();
    index_.reset();
}

void DepthModel::addReference(DepthCloud cloud, const Eigen::Isometry3d& T_new_old, bool pinned) {
    if (!pinned) keyframes_.clear();
    for (Keyframe& k : keyframes_) k.T_ref_kf = T_new_old * k.T_ref_kf;
    keyframes_.push_back({std::move(cloud), Eigen::Isometry3d::Identity()});
    while (static_cast<int>(keyframes_.size()) > max_keyframes_) keyframes_.pop_front();
    index_.reset();
}

std::size_t DepthModel::size() const {
    std::size_t n = 0;
    for (const Keyframe& k : keyframes_) n += k.cloud.size();
    return n;
}

void DepthModel::build() const {
    index_ = std::make_unique<Index>();
    const auto n = static_cast<Eigen::Index>(size());
    DepthCloud& m = index_->merged;
    m.points.resize(3, n);
    m.normals.resize(3, n);
    m.sigma.resize(n);
    m.normalVariance.resize(n);
    Eigen::Index at = 0;
    for (const Keyframe& k : keyframes_) {
        const DepthCloud moved = k.cloud.transformed(k.T_ref_kf.cast<float>());
        const auto c = static_cast<Eigen::Index>(moved.size());
        m.points.middleCols(at, c) = moved.points;
        m.normals.middleCols(at, c) = moved.normals;
        m.sigma.segment(at, c) = moved.sigma;
        m.normalVariance.segment(at, c) = moved.normalVariance;
        at += c;
    }
    index_->tree = std::make_unique<Index::Tree>(3, *index_, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    index_->tree->buildIndex();
}

bool DepthModel::nearest(const Eigen::Vector3f& p, float maxDistance2, Nearest& out,
                         std::int64_t near) const {
    if (keyframes_.empty()) return false;
    if (!index_) build();
    if (index_->merged.size() == 0) return false;
    float bound = maxDistance2;
    if (near >= 0 && near < static_cast<std::int64_t>(index_->merged.size())) {
        // Widened past rounding: a larger bound never changes the answer (the nearest point
        // and, among equally near ones, the first the traversal meets), a smaller one might.
        const float d2 = (p - index_->merged.points.col(static_cast<Eigen::Index>(near))).squaredNorm();
        bound = std::min(bound, d2 * (1 + 1e-4f) + 1e-12f);
    }
    NearestWithin result(bound);
    index_->tree->findNeighbors(result, p.data(), nanoflann::SearchParams(32, 0, false));
    if (!result.found) return false;
    const float d2 = result.best;
    const auto i = static_cast<Eigen::Index>(result.index);
    out.point = index_->merged.points.col(i);
    out.normal = index_->merged.normals.col(i);
    out.sigma = index_->merged.sigma(i);
    out.normalVariance = index_->merged.normalVariance(i);
    out.distance2 = d2;
    out.index = static_cast<std::int64_t>(i);
    return true;
}

}  // namespace lodestone::vision
