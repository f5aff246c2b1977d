#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>
#include <lodestone/magnetic/HyperparameterFit.h>

#include <cmath>

namespace lodestone::magnetic {

namespace {
GpHyperparameters fromLog(const double* p) {
    GpHyperparameters h;
    h.sigmaF = std::exp(p[0]);
    h.lengthScale = std::exp(p[1]);
    h.sigmaN = std::exp(p[2]);
    h.sigmaC = std::exp(p[3]);
    return h;
}

/** Ceres minimizes: the negative summed log marginal likelihood. */
class NegativeLogMarginal : public ceres::FirstOrderFunction {
  public:
    explicit NegativeLogMarginal(const std::vector<FieldStretch>& s) : stretches_(s) {}
    bool Evaluate(const double* p, double* cost, double* gradient) const override {
        const auto h = fromLog(p);
        double total = 0;
        Eigen::Vector4d g = Eigen::Vector4d::Zero();
        for (const auto& s : stretches_) {
            Eigen::Vector4d gs;
            const double v =
                GaussianProcess1D::logMarginal(s.travel, s.readings, h, gradient ? &gs : nullptr);
            if (!std::isfinite(v)) return false;
            total += v;
            if (gradient) g += gs;
        }
        *cost = -total;
        if (gradient) {
            for (int k = 0; k < 4; ++k) gradient[k] = -g[k];
        }
        return true;
    }
    int NumParameters() const override { return 4; }

  private:
    const std::vector<FieldStretch>& stretches_;
};
}  // namespace

HyperparameterFitResult fitHyperparameters(const std::vector<FieldStretch>& stretches,
                                           const GpHyperparameters& start) {
    double p[4] = {std::log(start.sigmaF), std::log(start.lengthScale), std::log(start.sigmaN),
                   std::log(std::max(start.sigmaC, 1e-3))};
    ceres::GradientProblem problem(new NegativeLogMarginal(stretches));
    ceres::GradientProblemSolver::Options options;
    options.max_num_iterations = 200;
    options.logging_type = ceres::SILENT;
    ceres::GradientProblemSolver::Summary summary;
    ceres::Solve(options, problem, p, &summary);
    HyperparameterFitResult r;
    r.hyperparameters = fromLog(p);
    r.logMarginal = -summary.final_cost;
    r.iterations = static_cast<int>(summary.iterations.size());
    r.converged = summary.termination_type == ceres::CONVERGENCE;
    return r;
}

}  // namespace lodestone::magnetic
