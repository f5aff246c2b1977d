#include <lodestone/vision/depth/DepthModel.h>

#include <nanoflann.hpp>

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

bool DepthModel::nearest(const Eigen::Vector3f& p, float maxDistance2, Nearest& out) const {
    if (keyframes_.empty()) return false;
    if (!index_) build();
    if (index_->merged.size() == 0) return false;
    std::size_t idx = 0;
    float d2 = 0;
    nanoflann::KNNResultSet<float> result(1);
    result.init(&idx, &d2);
    index_->tree->findNeighbors(result, p.data(), nanoflann::SearchParams(32, 0, false));
    if (result.size() == 0 || d2 > maxDistance2) return false;
    const auto i = static_cast<Eigen::Index>(idx);
    out.point = index_->merged.points.col(i);
    out.normal = index_->merged.normals.col(i);
    out.sigma = index_->merged.sigma(i);
    out.normalVariance = index_->merged.normalVariance(i);
    out.distance2 = d2;
    return true;
}

}  // namespace lodestone::vision
