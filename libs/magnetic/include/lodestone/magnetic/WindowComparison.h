#pragma once

#include <lodestone/magnetic/SupernodeTrack.h>

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <vector>

namespace lodestone::magnetic {

/** Which way a query window runs over the stretch it is compared with: Forward pairs the
 * query's k-th reading with the target's k-th (the place walked the same way again),
 * Backward with the target's (n-1-k)-th (walked back). */
enum class WindowDirection { Forward, Backward };

/** One query window against one target window of levelled robot-frame readings (x forward,
 * y left, z up: the frame a heading-aligned magnetometer reports in). */
struct WindowFit {
    /** -2 log-likelihood of the differences: the sum of squared component differences over
     * sigma^2 at the best turn, plus the turn's prior term ((turn - prior)^2 / variance). */
    double chi2{INFINITY};
    double turnPriorChi2{0};  ///< the turn's prior term alone
    double turn{0};          ///< [rad] the query's heading minus the target's, from the field
    double turnVariance{0};  ///< [rad^2] its posterior variance
};

/** Compares `n` readings of `samples` from `query` (oldest first) with `n` from `target`,
 * paired by `direction`. The horizontal components of a reading turn with the robot's
 * heading, so the target's are turned by the relative heading that fits best under the prior
 * N(`turnPrior`, `turnPriorVariance`) (an infinite variance: no prior, after a kidnap); the
 * vertical component does not turn. `sigma` [uT]: how well one reading repeats between two
 * passes of the same place (per component, the difference's sigma). Samples need 3 channels. */
WindowFit compareWindows(const std::vector<TrackSample>& samples, std::size_t query,
                         std::size_t target, std::size_t n, WindowDirection direction,
                         double sigma, double turnPrior, double turnPriorVariance);

/** The differences of compareWindows' pairs at `fit`'s turn (n x 3, query minus turned target). */
Eigen::MatrixX3d windowResiduals(const std::vector<TrackSample>& samples, std::size_t query,
                                 std::size_t target, std::size_t n, WindowDirection direction,
                                 const WindowFit& fit);

/** How much likelier a window's differences are under "the same place" (each component
 * N(0, sigma^2), independent) than under "two unrelated places": each component then differs
 * as two independent draws of the field's anomalies along the path do, N(0, 2 K + sigma^2 I)
 * with K the squared-exponential kernel (sigmaF, lengthScale) of lodestone-magfit's fit over
 * the window's sample spacing. A chance look-alike far away fits no better than two unrelated
 * stretches usually do; the log ratio says by how much better this one does. */
class WindowNullModel {
  public:
    WindowNullModel(std::size_t n, double step, double sigma, double sigmaF, double lengthScale);
    /** log p(d | same place) - log p(d | unrelated places) for the residuals `d` (n x 3). */
    double logLikelihoodRatio(const Eigen::MatrixX3d& d) const;

  private:
    Eigen::MatrixXd nullInverse_;
    double sigma2_{1}, logNormalizers_{0};
};

/** sum_k |q_k - mean(q)|^2 / sigma^2 over the window [first, first + n): how far the field
 * there is from flat, in units of the noise (chi-square with 3(n-1) dof if it were flat). */
double windowExcitation(const std::vector<TrackSample>& samples, std::size_t first, std::size_t n,
                        double sigma);

/** The `p` quantile of the chi-square distribution with `dof` degrees of freedom
 * (Wilson-Hilferty; within 1 % for dof >= 3 at p in [0.9, 0.9999]). */
double chiSquareQuantile(double dof, double p);

}  // namespace lodestone::magnetic
