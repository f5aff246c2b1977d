#include <lodestone/magnetic/SupernodeTrack.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace lodestone::magnetic {

SupernodeTrack::SupernodeTrack(const Params& params, int channels)
    : params_(params), channels_(channels), resampler_(params.step) {
    if (!(params.length > params.step) || !(params.stride > 0) || channels < 1) {
        throw std::invalid_argument("SupernodeTrack: need length > step > 0, stride > 0");
    }
    per_supernode_ = static_cast<std::size_t>(std::lround(params.length / params.step));
    stride_samples_ = std::max<std::size_t>(
        1, static_cast<std::size_t>(std::lround(params.stride / params.step)));
}

std::vector<Supernode> SupernodeTrack::add(double s, const Eigen::VectorXd& feature,
                                           std::size_t node, int segment) {
    std::vector<Supernode> out;
    if (feature.size() != channels_)
        throw std::invalid_argument("SupernodeTrack: wrong channel count");
    if (!started_ || segment != segment_) {
        resampler_.reset();
        segment_ = segment;
        segment_start_ = samples_.size();
        next_end_ = segment_start_ + per_supernode_;
        started_ = true;
    }
    node_ = node;
    for (const auto& r : resampler_.add(s, feature)) {
        samples_.push_back({r.s, r.value.cast<float>(), node_, segment_});
        emitIfDue(out);
    }
    return out;
}

void SupernodeTrack::emitIfDue(std::vector<Supernode>& out) {
    if (samples_.size() < next_end_) return;
    Supernode sn;
    sn.id = supernodes_.size();
    sn.last = samples_.size();
    sn.first = sn.last - per_supernode_;
    sn.segment = segment_;
    const auto n = static_cast<Eigen::Index>(per_supernode_);
    Eigen::MatrixXf block(n, channels_);
    for (Eigen::Index i = 0; i < n; ++i) block.row(i) = samples_[sn.first + i].value.transpose();
    sn.mean = block.colwise().mean().transpose();
    block.rowwise() -= sn.mean.transpose();
    sn.spread = std::sqrt((block.array().square().colwise().sum() / float(n)).maxCoeff());
    const Eigen::MatrixXf sampleMajor = block.transpose();  // column k = sample k's channels
    sn.vector = Eigen::Map<const Eigen::VectorXf>(sampleMajor.data(), sampleMajor.size());
    supernodes_.push_back(sn);
    out.push_back(std::move(sn));
    next_end_ += stride_samples_;
}

float SupernodeTrack::cost(const Supernode& a, const Supernode& b) {
    if (a.vector.size() != b.vector.size() || a.vector.size() == 0) {
        return std::numeric_limits<float>::infinity();
    }
    // Shape and level: the per-channel means are part of the place (the same sensor reads the
    // same mean there), compared beside the shape.
    const float shape = (a.vector - b.vector).squaredNorm();
    const float level = (a.mean - b.mean).squaredNorm() * float(a.vector.size() / a.mean.size());
    return std::sqrt((shape + level) / float(a.vector.size()));
}

float SupernodeTrack::costAt(const Supernode& q, std::size_t first) const {
    const std::size_t n = per_supernode_;
    if (first + n > samples_.size() || q.vector.size() != static_cast<Eigen::Index>(n) * channels_)
        return std::numeric_limits<float>::infinity();
    const int segment = samples_[first].segment;
    if (samples_[first + n - 1].segment != segment) return std::numeric_limits<float>::infinity();
    Eigen::VectorXf mean = Eigen::VectorXf::Zero(channels_);
    for (std::size_t i = 0; i < n; ++i) mean += samples_[first + i].value;
    mean /= float(n);
    float shape = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const auto qi = q.vector.segment(static_cast<Eigen::Index>(i) * channels_, channels_);
        shape += (qi - (samples_[first + i].value - mean)).squaredNorm();
    }
    const float level = (q.mean - mean).squaredNorm() * float(n);
    return std::sqrt((shape + level) / float(q.vector.size()));
}

std::pair<float, std::size_t> SupernodeTrack::alignedCost(const Supernode& q, const Supernode& t,
                                                          std::size_t maxShift) const {
    std::pair<float, std::size_t> best{cost(q, t), t.first};
    for (std::size_t k = 1; k <= maxShift; ++k) {
        for (const std::size_t first : {t.first + k, t.first >= k ? t.first - k : t.first}) {
            if (first == t.first) continue;
            const float c = costAt(q, first);
            if (c < best.first) best = {c, first};
        }
    }
    return best;
}

}  // namespace lodestone::magnetic
