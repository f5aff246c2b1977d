#pragma once

#include <Eigen/Core>

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

}  // namespace lodestone::magnetic
