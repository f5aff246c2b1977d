// MagneticWindowERD's query window in the map's frame: its readings turned by the graph's
// headings, and what they say of the window as evidence - its spread, its excitation (a turn's
// readings weighed by how well their heading is known), its fine-scale amplitude, its turn.
#include <lodestone/graphslam/erd/magnetic/MagneticWindowERD.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace lodestone::graphslam {

double MagneticWindowERD::windowSpread(double excitation) const {
    // The window's spread about its mean, the reading noise (half the difference's variance)
    // taken out. A stretch that varies little is no strong evidence when it matches another
    // that varies little.
    const double dof = 3.0 * double(n_);
    const double s2 = params_.noise.sigma * params_.noise.sigma;
    const double spread2 = excitation * s2 / (dof - 3) - 0.5 * s2;
    return std::sqrt(std::max(spread2, 1e-6));
}

std::vector<Eigen::Vector3d> MagneticWindowERD::mapFrameWindow(std::size_t first) const {
    const auto& samples = queried().samples();
    std::vector<Eigen::Vector3d> b(n_);
    for (std::size_t k = 0; k < n_; ++k) {
        const Eigen::Vector3d v = samples[first + k].value.head<3>().cast<double>();
        const double yaw = yawAtSample(queried(), first + k), c = std::cos(yaw), s = std::sin(yaw);
        b[k] = {c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z()};
    }
    return b;
}

double MagneticWindowERD::fineAmplitude(std::size_t first) const {
    const auto lag = static_cast<std::size_t>(
        std::clamp(std::lround(params_.lengthScale / params_.step), 1L, long(n_) - 1));
    const double h = double(lag) * params_.step / params_.lengthScale;
    const auto meanSquareStep = [&](const std::vector<Eigen::Vector3d>& b) {
        double sum = 0;
        for (std::size_t k = 0; k + lag < b.size(); ++k) sum += (b[k + lag] - b[k]).squaredNorm();
        return sum / (3.0 * double(b.size() - lag));
    };
    std::vector<Eigen::Vector3d> robot(n_);
    for (std::size_t k = 0; k < n_; ++k)
        robot[k] = queried().samples()[first + k].value.head<3>().cast<double>();
    const double d2 = std::min(meanSquareStep(robot), meanSquareStep(mapFrameWindow(first)));
    return std::sqrt(std::max(d2 / (2 * -std::expm1(-0.5 * h * h)), 1e-6));
}

double MagneticWindowERD::mapFrameExcitation(std::size_t first) const {
    // A sample's heading is interpolated over its node's interval, but its readings may lie in
    // the interval before (a bin is closed by the first reading past it): where the carrier
    // turned by dpsi over the two, the heading is known to dpsi / sqrt(12) (uniform), and the
    // horizontal field's direction no better - a turn's readings weigh less, not more.
    const auto b = mapFrameWindow(first);
    const auto& samples = queried().samples();
    const double n2 = params_.noise.sigma * params_.noise.sigma;
    std::vector<double> variance(n_);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    double weights = 0;
    for (std::size_t k = 0; k < n_; ++k) {
        const auto node = static_cast<TNodeID>(samples[first + k].node);
        TNodeID from = node;  // the interval's start: up to two nodes back, in its segment
        while (from + 2 > node && from > 0 && path_.segment[from - 1] == path_.segment[node])
            --from;
        const double turn = std::remainder(poses_[node]->yaw() - poses_[from]->yaw(), 2 * M_PI);
        variance[k] = n2 + b[k].head<2>().squaredNorm() * turn * turn / 12;
        mean += b[k] / variance[k];
        weights += 1 / variance[k];
    }
    mean /= weights;
    double sum = 0;
    for (std::size_t k = 0; k < n_; ++k) sum += (b[k] - mean).squaredNorm() / variance[k];
    return sum;
}

double MagneticWindowERD::mapFrameSpread(std::size_t first) const {
    const auto b = mapFrameWindow(first);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& v : b) mean += v;
    mean /= double(n_);
    double sum = 0;
    for (const auto& v : b) sum += (v - mean).squaredNorm();
    return windowSpread(sum / (params_.noise.sigma * params_.noise.sigma));
}

double MagneticWindowERD::windowTurn(const magnetic::SupernodeTrack& track,
                                     std::size_t start) const {
    const auto& samples = track.samples();
    return std::remainder(
        poses_[samples[start + n_ - 1].node]->yaw() - poses_[samples[start].node]->yaw(), 2 * M_PI);
}

double MagneticWindowERD::nearRadius(double turn) const {
    return params_.distinctRadius / std::sqrt(1 + turn * turn / 4);
}

}  // namespace lodestone::graphslam
