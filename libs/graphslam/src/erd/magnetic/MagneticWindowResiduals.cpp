// MagneticWindowERD's residuals of a query window against a candidate's, directly and in the
// noise's eigenbasis (the stored windows' projections kept: each is compared with many queries).
#include <lodestone/graphslam/erd/magnetic/MagneticWindowERD.h>

#include <algorithm>
#include <cmath>

namespace lodestone::graphslam {

using magnetic::WindowDirection;

Eigen::MatrixX3d MagneticWindowERD::residuals(const Candidate& k, std::size_t first) const {
    return magnetic::windowResiduals(
        queried().samples(), first, k.track->samples(),
        k.direction == WindowDirection::Forward ? k.sample + 1 - n_ : k.sample, n_, k.direction,
        k.fit);
}

Eigen::MatrixX3d MagneticWindowERD::projectedWindow(const magnetic::SupernodeTrack& track,
                                                    std::size_t start, bool reversed) const {
    Eigen::MatrixX3d w(static_cast<Eigen::Index>(n_), 3);
    const auto& samples = track.samples();
    for (std::size_t k = 0; k < n_; ++k)
        w.row(static_cast<Eigen::Index>(k)) =
            samples[reversed ? start + n_ - 1 - k : start + k].value.head<3>().cast<double>();
    return basis_->toEigenbasis.lazyProduct(w);
}

std::uint64_t MagneticWindowERD::projectionKey(const magnetic::SupernodeTrack& track,
                                               std::size_t start, bool backward) const {
    return (std::uint64_t(start) << 2) | (&track == &queried() ? 0u : 2u) | (backward ? 1u : 0u);
}

Eigen::MatrixX3d MagneticWindowERD::projectedResiduals(const Candidate& k, std::size_t start,
                                                       const Eigen::MatrixX3d& query) const {
    // A stored window is compared with many queries: its projection is kept (the stored
    // readings a candidate's window holds are final, min_travel_gap behind the robot).
    const bool backward = k.direction == WindowDirection::Backward;
    const std::uint64_t key = projectionKey(*k.track, start, backward);
    const Eigen::MatrixX3d* projected = nullptr;
    if (const auto m = projected_map_.find(key); m != projected_map_.end()) {
        projected = &m->second;
    } else {
        auto it = projected_targets_.find(key);
        if (it == projected_targets_.end()) {
            if (projected_targets_.size() >= kProjectionCache) projected_targets_.clear();
            it = projected_targets_.emplace(key, projectedWindow(*k.track, start, backward)).first;
        }
        projected = &it->second;
    }
    // The differences, as windowResiduals forms them, in the basis (a linear map).
    const Eigen::MatrixX3d& t = *projected;
    const double c = std::cos(k.fit.turn), s = std::sin(k.fit.turn);
    Eigen::MatrixX3d d(query.rows(), 3);
    d.col(0) = query.col(0) - (c * t.col(0) + s * t.col(1));
    d.col(1) = query.col(1) - (-s * t.col(0) + c * t.col(1));
    d.col(2) = query.col(2) - t.col(2);
    return d;
}

}  // namespace lodestone::graphslam
