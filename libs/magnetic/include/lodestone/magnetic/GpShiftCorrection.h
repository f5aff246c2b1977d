#pragma once

#include <lodestone/magnetic/GaussianProcess1D.h>

#include <vector>

namespace lodestone::magnetic {

/** Paper 000 eq. (3), the GP linear correction: a GP fitted to the target bundle's field along
 * its path; the query bundle, slid along the path by x, is scored by the GP's predictive
 * likelihood; x* maximizes it (a scan at `step`, then a golden-section refinement). */
struct ShiftResult {
    bool valid{false};
    double shift{0};  ///< x* [m]: query travel + x* lands on the target's travel
    double sigma{0};  ///< its standard deviation from the likelihood's curvature [m]
    double logLikelihood{0};
    /** RMS of the residuals at x*, each divided by its predictive standard deviation: about 1
     * when the query fits the target's field, much more when it does not. */
    double normalizedRms{0};
};

struct ShiftScanParams {
    double maxShift{0.5};   ///< scan range +-[m]
    double step{0.02};      ///< scan step [m]
    double minSigma{0.01};  ///< floor on the reported sigma [m]
};

/** `gp` is fitted on the target; `queryTravel` are the query readings' positions in the
 * target's travel coordinates before the shift, `query` their readings (m x channels). */
ShiftResult scanShift(const GaussianProcess1D& gp, const std::vector<double>& queryTravel,
                      const Eigen::MatrixXd& query, const ShiftScanParams& params);

}  // namespace lodestone::magnetic
