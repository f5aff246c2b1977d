#pragma once

#include <lodestone/magnetic/GaussianProcess1D.h>

#include <vector>

namespace lodestone::magnetic {

/** Stretches of field along a path (travel [m], readings n x channels) to fit on. */
struct FieldStretch {
    std::vector<double> travel;
    Eigen::MatrixXd readings;
};

struct HyperparameterFitResult {
    GpHyperparameters hyperparameters;
    double logMarginal{0};  ///< at the optimum, summed over the stretches
    int iterations{0};
    bool converged{false};
};

/** Maximizes the summed log marginal likelihood of the stretches over the hyperparameters
 * (L-BFGS in log space with the analytic gradient, Ceres' GradientProblemSolver), from
 * `start`. */
HyperparameterFitResult fitHyperparameters(const std::vector<FieldStretch>& stretches,
                                           const GpHyperparameters& start);

}  // namespace lodestone::magnetic
