#include <lodestone/magnetic/SupernodeIndex.h>

#include <nanoflann.hpp>

namespace lodestone::magnetic {

namespace {
/** nanoflann's view of the stored summaries (row-major, `dim` floats each). */
struct Summaries {
    std::vector<float> data;
    std::vector<std::size_t> ids;
    std::size_t dim{0};
    std::size_t kdtree_get_point_count() const { return ids.size(); }
    float kdtree_get_pt(std::size_t i, std::size_t d) const { return data[i * dim + d]; }
    template <class BBox>
    bool kdtree_get_bbox(BBox&) const {
        return false;
    }
};
using Tree =
    nanoflann::KDTreeSingleIndexDynamicAdaptor<nanoflann::L2_Simple_Adaptor<float, Summaries>,
                                               Summaries, -1>;
}  // namespace

struct SupernodeIndex::Impl {
    int channels;
    std::size_t samples;
    int bins;
    Summaries points;
    std::unique_ptr<Tree> tree;
};

SupernodeIndex::SupernodeIndex(int channels, std::size_t samplesPerSupernode, int bins)
    : impl_(std::make_unique<Impl>()) {
    impl_->channels = channels;
    impl_->samples = samplesPerSupernode;
    impl_->bins = std::max(1, std::min<int>(bins, static_cast<int>(samplesPerSupernode)));
    impl_->points.dim = static_cast<std::size_t>(impl_->bins * channels);
    impl_->tree = std::make_unique<Tree>(static_cast<int>(impl_->points.dim), impl_->points,
                                         nanoflann::KDTreeSingleIndexAdaptorParams(10));
}

SupernodeIndex::~SupernodeIndex() = default;

std::vector<float> SupernodeIndex::summary(const Supernode& s) const {
    const auto& I = *impl_;
    std::vector<float> out(I.points.dim, 0.0f);
    std::vector<int> count(static_cast<std::size_t>(I.bins), 0);
    for (std::size_t k = 0; k < I.samples; ++k) {
        const std::size_t b = k * static_cast<std::size_t>(I.bins) / I.samples;
        ++count[b];
        for (int c = 0; c < I.channels; ++c) {
            out[b * I.channels + c] +=
                s.vector[static_cast<Eigen::Index>(k * I.channels + c)] + s.mean[c];
        }
    }
    // Averages scaled by sqrt(samples per bin): summary distances then approximate the full
    // L2 distance between the raw sequences.
    for (std::size_t b = 0; b < count.size(); ++b) {
        for (int c = 0; c < I.channels; ++c) {
            out[b * I.channels + c] *= 1.0f / std::sqrt(static_cast<float>(count[b]));
        }
    }
    return out;
}

void SupernodeIndex::add(const Supernode& s) {
    auto& I = *impl_;
    const auto v = summary(s);
    I.points.data.insert(I.points.data.end(), v.begin(), v.end());
    I.points.ids.push_back(s.id);
    const auto i = static_cast<uint32_t>(I.points.ids.size() - 1);
    I.tree->addPoints(i, i);
}

std::size_t SupernodeIndex::size() const { return impl_->points.ids.size(); }

std::vector<std::size_t> SupernodeIndex::nearest(const Supernode& s, std::size_t k) const {
    const auto& I = *impl_;
    k = std::min(k, I.points.ids.size());
    if (k == 0) return {};
    const auto q = summary(s);
    std::vector<uint32_t> idx(k);
    std::vector<float> dist(k);
    nanoflann::KNNResultSet<float, uint32_t> result(k);
    result.init(idx.data(), dist.data());
    I.tree->findNeighbors(result, q.data(), nanoflann::SearchParams());
    std::vector<std::size_t> out;
    for (std::size_t j = 0; j < result.size(); ++j) out.push_back(I.points.ids[idx[j]]);
    return out;
}

}  // namespace lodestone::magnetic
