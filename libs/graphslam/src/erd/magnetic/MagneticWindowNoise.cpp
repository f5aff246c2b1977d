// MagneticWindowERD with learn_noise: the pass noise learnt from the run's own closed windows
// (magnetic::PassNoiseEstimate, window_sigma its prior), the tests following the estimate.
#include <lodestone/graphslam/erd/magnetic/MagneticWindowERD.h>

#include <cmath>
#include <vector>

namespace lodestone::graphslam {

void MagneticWindowERD::learnNoise(const Candidate& best, std::size_t first) {
    // Windows that overlap share readings: one in each window's length.
    const double s = queried().samples()[first + n_ - 1].s;
    if (s - last_learnt_ < params_.window) return;
    last_learnt_ = s;
    noise_->add(residuals(best, first));
    const double sigma = noise_->sigma();
    if (std::abs(sigma / params_.noise.sigma - 1) <= 0.1) return;
    params_.noise.sigma = sigma;
    ++stats_.noiseUpdates;
    rebuildBasis();
}

void MagneticWindowERD::rebuildBasis() {
    basis_ = std::make_shared<const magnetic::WindowDisplacementModel::Basis>(n_, params_.noise,
                                                                              params_.lengthScale);
    projected_targets_.clear();
    if (!projected_map_.empty()) {
        projected_map_.clear();
        projectMapTargets();
    }
}

bool MagneticWindowERD::noiseLearnt() const {
    return noise_ && noise_->dof() >= noise_->priorDof();
}

bool MagneticWindowERD::stretchFlat(std::size_t first) const {
    // The windows before the query's, as many as a chain gathers, in its segment. Over a
    // stretch the graph's heading drifts - in the map frame an even field varies by it, in the
    // robot frame by every turn - so its flatness is judged in the channels that know no
    // heading: the vertical part and the horizontal magnitude.
    const auto& samples = queried().samples();
    const std::size_t newest = first + n_ - 1;
    std::size_t count = n_;
    while (count < std::size_t(params_.chainWindows) * n_ && newest + 1 >= count + n_ &&
           samples[newest + 1 - count - n_].segment == samples[newest].segment)
        count += n_;
    if (count == n_) return true;
    const std::size_t from = newest + 1 - count;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    std::vector<Eigen::Vector2d> invariant(count);
    for (std::size_t k = 0; k < count; ++k) {
        const auto& v = samples[from + k].value;
        invariant[k] = {std::hypot(double(v[0]), double(v[1])), double(v[2])};
        mean += invariant[k];
    }
    mean /= double(count);
    double sum = 0;
    for (const auto& v : invariant) sum += (v - mean).squaredNorm();
    return sum / (params_.noise.sigma * params_.noise.sigma) <
           magnetic::chiSquareQuantile(2.0 * double(count - 1), params_.quantile);
}

}  // namespace lodestone::graphslam
