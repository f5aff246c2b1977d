#include <lodestone/magnetic/GpShiftCorrection.h>

#include <algorithm>
#include <cmath>

namespace lodestone::magnetic {

namespace {
/** The GP's prediction on a fine grid over every position a shifted query can reach, so that
 * scoring a shift is a linear interpolation per reading instead of a GP prediction (the field
 * is smooth on the grid's scale: spacing << length scale). */
class PredictionGrid {
  public:
    PredictionGrid(const GaussianProcess1D& gp, double from, double to, double spacing)
        : from_(from), spacing_(spacing) {
        const auto n = static_cast<std::size_t>(std::ceil((to - from) / spacing)) + 2;
        std::vector<double> xs(n);
        for (std::size_t i = 0; i < n; ++i) xs[i] = from + spacing * static_cast<double>(i);
        gp.predict(xs, mean_, var_);
    }
    /** Log-likelihood of the readings at `travel` + x, and optionally the normalized RMS. */
    double score(const std::vector<double>& travel, const Eigen::MatrixXd& query, double x,
                 double* normalizedRms = nullptr) const {
        double ll = 0, z2 = 0;
        const auto C = query.cols();
        for (std::size_t i = 0; i < travel.size(); ++i) {
            const double u = (travel[i] + x - from_) / spacing_;
            const auto k = static_cast<Eigen::Index>(
                std::clamp(std::floor(u), 0.0, static_cast<double>(var_.size() - 2)));
            const double f = std::clamp(u - static_cast<double>(k), 0.0, 1.0);
            const double var = (1 - f) * var_[k] + f * var_[k + 1];
            const auto row = static_cast<Eigen::Index>(i);
            double r2 = 0;
            for (Eigen::Index c = 0; c < C; ++c) {
                const double r = query(row, c) - ((1 - f) * mean_(k, c) + f * mean_(k + 1, c));
                r2 += r * r;
            }
            ll -= 0.5 * (r2 / var + static_cast<double>(C) * std::log(2 * M_PI * var));
            z2 += r2 / var;
        }
        if (normalizedRms) *normalizedRms = std::sqrt(z2 / static_cast<double>(query.size()));
        return ll;
    }

  private:
    double from_, spacing_;
    Eigen::MatrixXd mean_;
    Eigen::VectorXd var_;
};
}  // namespace

ShiftResult scanShift(const GaussianProcess1D& gp, const std::vector<double>& travel,
                      const Eigen::MatrixXd& query, const ShiftScanParams& p) {
    ShiftResult r;
    if (travel.empty() || !(p.step > 0) || !(p.maxShift >= 0)) return r;
    const auto [lo, hi] = std::minmax_element(travel.begin(), travel.end());
    const PredictionGrid grid(gp, *lo - p.maxShift - p.step, *hi + p.maxShift + p.step,
                              0.25 * p.step);
    const auto scoreAt = [&](const GaussianProcess1D&, const std::vector<double>& t,
                             const Eigen::MatrixXd& q, double x) { return grid.score(t, q, x); };
    const int half = static_cast<int>(std::floor(p.maxShift / p.step + 1e-9));
    double best = -std::numeric_limits<double>::infinity();
    int bestK = 0;
    for (int k = -half; k <= half; ++k) {
        const double s = scoreAt(gp, travel, query, k * p.step);
        if (s > best) {
            best = s;
            bestK = k;
        }
    }
    // On the scan's edge the optimum may lie outside the range: no answer rather than a clipped
    // one.
    if (half > 0 && std::abs(bestK) == half) return r;
    // Golden-section search within one step either side of the best grid point.
    const double phi = 0.5 * (std::sqrt(5.0) - 1);
    double a = (bestK - 1) * p.step, b = (bestK + 1) * p.step;
    double c = b - phi * (b - a), d = a + phi * (b - a);
    double fc = scoreAt(gp, travel, query, c), fd = scoreAt(gp, travel, query, d);
    for (int it = 0; it < 20; ++it) {
        if (fc > fd) {
            b = d;
            d = c;
            fd = fc;
            c = b - phi * (b - a);
            fc = scoreAt(gp, travel, query, c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + phi * (b - a);
            fd = scoreAt(gp, travel, query, d);
        }
    }
    r.shift = 0.5 * (a + b);
    r.logLikelihood = scoreAt(gp, travel, query, r.shift);
    // Curvature by central differences: sigma^2 = -1 / (d^2 LL / dx^2).
    const double h = 0.5 * p.step;
    const double curvature = (scoreAt(gp, travel, query, r.shift + h) - 2 * r.logLikelihood +
                              scoreAt(gp, travel, query, r.shift - h)) /
                             (h * h);
    r.sigma = curvature < 0 ? std::max(p.minSigma, std::sqrt(-1 / curvature)) : p.maxShift;
    grid.score(travel, query, r.shift, &r.normalizedRms);
    r.valid = true;
    return r;
}

}  // namespace lodestone::magnetic
