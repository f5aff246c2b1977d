#include <lodestone/magnetic/PassNoiseEstimate.h>

#include <cmath>
#include <stdexcept>

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

}  // namespace lodestone::magnetic
