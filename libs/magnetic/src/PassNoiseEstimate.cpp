#include <lodestone/magnetic/PassNoiseEstimate.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>

namespace lodestone::magnetic {

PassNoiseEstimate::PassNoiseEstimate(double priorSigma, double priorDof)
    : prior_sigma2_(priorSigma * priorSigma), prior_dof_(priorDof) {
    if (!(priorSigma > 0) || !(priorDof > 0))
        throw std::invalid_argument("PassNoiseEstimate: prior sigma and dof must be > 0");
}

void PassNoiseEstimate::add(const Eigen::MatrixX3d& differences, double fitted) {
    if (!differences.allFinite() || differences.rows() == 0) return;
    sum_ += differences.squaredNorm();
    dof_ += std::max(0.0, double(differences.size()) - fitted);
}

double PassNoiseEstimate::sigma() const {
    return std::sqrt((prior_dof_ * prior_sigma2_ + sum_) / (prior_dof_ + dof_));
}

std::optional<double> passRepeatabilityAcrossPasses(const std::vector<Eigen::Vector2d>& positions,
                                                    const std::vector<Eigen::Vector3d>& fields,
                                                    const std::vector<double>& travel,
                                                    const std::vector<int>& segment, double radius,
                                                    double gap, std::size_t minPairs) {
    if (!(radius > 0) || positions.size() != fields.size() || positions.size() != travel.size() ||
        positions.size() != segment.size())
        throw std::invalid_argument("passRepeatabilityAcrossPasses: bad input");
    const auto cellOf = [&](const Eigen::Vector2d& p) {
        return std::make_pair(static_cast<std::int64_t>(std::floor(p.x() / radius)),
                              static_cast<std::int64_t>(std::floor(p.y() / radius)));
    };
    const auto key = [](std::int64_t x, std::int64_t y) {
        return (static_cast<std::uint64_t>(x) << 32) ^ (static_cast<std::uint64_t>(y) & 0xffffffffu);
    };
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells;
    for (std::size_t i = 0; i < positions.size(); ++i) {
        if (!positions[i].allFinite() || !fields[i].allFinite()) continue;
        const auto [cx, cy] = cellOf(positions[i]);
        cells[key(cx, cy)].push_back(i);
    }
    std::vector<double> d;
    for (std::size_t i = 0; i < positions.size(); ++i) {
        if (!positions[i].allFinite() || !fields[i].allFinite()) continue;
        const auto [cx, cy] = cellOf(positions[i]);
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
            for (std::int64_t dy = -1; dy <= 1; ++dy) {
                const auto it = cells.find(key(cx + dx, cy + dy));
                if (it == cells.end()) continue;
                for (const std::size_t j : it->second) {
                    if (j <= i) continue;  // each pair once
                    if (segment[i] == segment[j] && std::abs(travel[j] - travel[i]) < gap) continue;
                    if ((positions[j] - positions[i]).norm() > radius) continue;
                    const Eigen::Vector3d e = fields[j] - fields[i];
                    d.insert(d.end(), {e.x(), e.y(), e.z()});
                }
            }
        }
    }
    if (d.size() < 3 * minPairs) return std::nullopt;
    const auto median = [](std::vector<double> v) {
        const auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
        std::nth_element(v.begin(), mid, v.end());
        return *mid;
    };
    const double m = median(d);
    for (auto& v : d) v = std::abs(v - m);
    return 1.4826 * median(d) / std::sqrt(2.0);
}

}  // namespace lodestone::magnetic
