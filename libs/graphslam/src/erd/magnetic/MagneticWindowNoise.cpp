// MagneticWindowERD with learn_noise: the pass noise learnt from the run's own closed windows
// (magnetic::PassNoiseEstimate, window_sigma its prior), the tests following the estimate.
#include <lodestone/graphslam/erd/magnetic/MagneticWindowERD.h>

#include <cmath>

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

}  // namespace lodestone::graphslam
