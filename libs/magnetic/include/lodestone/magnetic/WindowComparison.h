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

/** How the readings of one place differ between two passes, per component: white noise of
 * `sigma` plus, over a window, a constant offset of `biasSigma` and a linear trend of
 * `trendSigma` per metre (a hand-held device's height and tilt, a sensor's slow drift: smooth
 * differences, which white noise alone would count again at every reading). */
struct PassNoise {
    double sigma{1.0};     ///< [uT]
    double biasSigma{0};   ///< [uT]
    double trendSigma{0};  ///< [uT/m]
    double step{0.05};     ///< [m] between a window's readings
};

/** One query window against one target window of levelled robot-frame readings (x forward,
 * y left, z up: the frame a heading-aligned magnetometer reports in). */
struct WindowFit {
    /** -2 log-likelihood of the differences (PassNoise's covariance, normalizer left out) at
     * the best turn, plus the turn's prior term ((turn - prior)^2 / variance). */
    double chi2{INFINITY};
    double turnPriorChi2{0};  ///< the turn's prior term alone
    double turn{0};           ///< [rad] the query's heading minus the target's, from the field
    double turnVariance{0};   ///< [rad^2] its posterior variance
};

/** Compares `n` readings of `querySamples` from `query` (oldest first) with `n` of
 * `targetSamples` from `target` (the same track, or another magnetometer's), paired by
 * `direction`. The horizontal components of a reading turn with the robot's
 * heading, so the target's are turned by the relative heading that fits best under the prior
 * N(`turnPrior`, `turnPriorVariance`) (an infinite variance: no prior, after a kidnap); the
 * vertical component does not turn (the turn is fitted under the white part of `noise`).
 * O(n): the offset and trend enter through the differences' sums. Samples need 3 channels. */
WindowFit compareWindows(const std::vector<TrackSample>& querySamples, std::size_t query,
                         const std::vector<TrackSample>& targetSamples, std::size_t target,
                         std::size_t n, WindowDirection direction, const PassNoise& noise,
                         double turnPrior, double turnPriorVariance);

/** The differences of compareWindows' pairs at `fit`'s turn (n x 3, query minus turned target). */
Eigen::MatrixX3d windowResiduals(const std::vector<TrackSample>& querySamples, std::size_t query,
                                 const std::vector<TrackSample>& targetSamples, std::size_t target,
                                 std::size_t n, WindowDirection direction, const WindowFit& fit);

/** How much likelier a window's differences are under "the same place" (each component
 * N(0, C1), C1 the PassNoise covariance, components independent) than under "two unrelated
 * places": each component then differs as two independent draws of the field's anomalies
 * along the path do, N(0, 2 K + C1) with K the squared-exponential kernel (sigmaF,
 * lengthScale) over the window's sample spacing. A chance look-alike far away fits no better
 * than two unrelated stretches usually do; the log ratio says by how much better this one does. */
class WindowNullModel {
  public:
    WindowNullModel(std::size_t n, const PassNoise& noise, double sigmaF, double lengthScale);
    /** log p(d | same place) - log p(d | unrelated places) for the residuals `d` (n x 3). */
    double logLikelihoodRatio(const Eigen::MatrixX3d& d) const;

  private:
    Eigen::MatrixXd same_inverse_, null_inverse_;
    double log_normalizers_{0};
};

/** The PassNoise covariance of one component over `n` readings (C1 above). */
Eigen::MatrixXd passNoiseCovariance(std::size_t n, const PassNoise& noise);

/** sum_k |q_k - mean(q)|^2 / sigma^2 over the window [first, first + n): how far the field
 * there is from flat, in units of the noise (chi-square with 3(n-1) dof if it were flat). */
double windowExcitation(const std::vector<TrackSample>& samples, std::size_t first, std::size_t n,
                        double sigma);

/** The `p` quantile of the chi-square distribution with `dof` degrees of freedom
 * (Wilson-Hilferty; within 1 % for dof >= 3 at p in [0.9, 0.9999]). */
double chiSquareQuantile(double dof, double p);

}  // namespace lodestone::magnetic
