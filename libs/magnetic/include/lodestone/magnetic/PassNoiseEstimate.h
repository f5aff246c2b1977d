#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

namespace lodestone::magnetic {

/** How the readings of one place differ between passes, learnt from the passes a run has
 * matched: white noise of variance sigma^2 per component, with a scaled-inverse-chi-square
 * prior of `priorSigma` worth `priorDof` readings, each matched window's differences adding
 * their squares and their count (the conjugate update). The posterior mean of sigma^2 is
 * (priorDof priorSigma^2 + sum of squares) / (priorDof + count): a wide prior gives way to
 * the run's own matches as they come, whatever the magnetometer or building. */
class PassNoiseEstimate {
  public:
    PassNoiseEstimate(double priorSigma, double priorDof);
    /** A matched window's differences (n x 3, query minus target at the fit; components
     * independent), `fitted` degrees of freedom spent on the fit (the relative heading). */
    void add(const Eigen::MatrixX3d& differences, double fitted = 1.0);
    /** [uT] the posterior mean of sigma^2, square-rooted. */
    double sigma() const;
    /** Readings' worth of evidence from the matches (the prior's not counted). */
    double dof() const { return dof_; }
    double priorDof() const { return prior_dof_; }

  private:
    double prior_sigma2_, prior_dof_, sum_{0}, dof_{0};
};

/** How a map's readings of one place differ between its passes: every pair of readings within
 * `radius` of each other on the floor (`positions`, where the map has them), from passes `gap`
 * or more of travel apart or from different segments (sessions), their per-component
 * differences' robust spread (1.4826 MAD) over sqrt 2 - per reading, sensor noise included.
 * Nothing with fewer than `minPairs` pairs (a map walked once). Grid-hashed: O(readings). */
std::optional<double> passRepeatabilityAcrossPasses(const std::vector<Eigen::Vector2d>& positions,
                                                    const std::vector<Eigen::Vector3d>& fields,
                                                    const std::vector<double>& travel,
                                                    const std::vector<int>& segment, double radius,
                                                    double gap, std::size_t minPairs = 30);

}  // namespace lodestone::magnetic
