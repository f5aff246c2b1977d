#pragma once

#include <lodestone/magnetic/WindowComparison.h>

#include <Eigen/Core>
#include <cstddef>
#include <memory>

namespace lodestone::magnetic {

/** What a window's differences say about how far apart two passes ran.
 *
 * Each component of the field's anomalies is modelled as a Gaussian process with variance
 * sigmaF^2 and a squared-exponential kernel of length scale l, the same in every direction in
 * space. Two passes along parallel lines `delta` apart then differ, reading by reading at the
 * same travel, with covariance
 *     C(delta) = C1 + 2 sigmaF^2 (1 - exp(-delta^2 / (2 l^2))) K
 * (K the kernel's correlation over the window's travel, C1 the PassNoise covariance). delta = 0
 * is the same line; delta -> infinity two unrelated places (WindowNullModel's alternative). The
 * differences' likelihood across delta measures the passes' distance - its magnitude only: an
 * isotropic field does not say which side. It is weighed under a prior on the distance across
 * the path (a half-normal of `priorSigma`: a robot, or a walker's height held, passes beside
 * and not above), integrated over bins of radius / 10 and split at a radius (near: the same
 * place; far: beside it). One eigendecomposition per window; a pair of windows then costs one
 * projection and O(n) per bin. */
class WindowDisplacementModel {
  public:
    /** The part that depends on the window alone (its length, noise and the kernel's length
     * scale, not the field's amplitude): C1 = L L', L^-1 K L^-T = U diag U'. Built once for
     * every window of one length. */
    struct Basis {
        Basis(std::size_t n, const PassNoise& noise, double lengthScale);
        Eigen::MatrixXd toEigenbasis;  ///< U' L^-1
        Eigen::VectorXd eigenvalues;
        double lengthScale{1};
    };
    /** `unrelatedSigmaF` (NaN: `sigmaF`): the amplitude of the null alone. A field of two
     * scales - a broad part that passes beside each other share and unrelated places do not,
     * over a fine part of amplitude `sigmaF` that differs as they move apart - is this model
     * with the broad part's scale taken as infinite: passes beside differ by the fine part
     * only, unrelated places by the whole spread. */
    WindowDisplacementModel(std::shared_ptr<const Basis> basis, double sigmaF, double priorSigma,
                            double radius, double unrelatedSigmaF = NAN);
    WindowDisplacementModel(std::size_t n, const PassNoise& noise, double sigmaF,
                            double lengthScale, double priorSigma, double radius);

    /** The differences `d` (n x 3) weighed under the prior on the passes' distance, split at
     * `nearRadius` (<= the constructor's radius; rounded down to a bin, at least one). */
    struct Evidence {
        double logNear{0};     ///< log of p(d, delta <= near radius) / p(d | unrelated places)
        double logFar{0};      ///< log of p(d, delta > near radius) / p(d | unrelated places)
        double nearDelta2{0};  ///< E[delta^2 | d, delta <= near radius] [m^2]
        /** d' C(near radius)^-1 d: chi-square with 3n dof if the passes ran that far apart. */
        double chi2AtRadius{0};
        /** log p(d | unrelated places), up to a constant shared by every window of the basis:
         * logNear + logUnrelated is log p(d, delta <= near radius) on the same footing, to
         * weigh against another null (MagneticWindowERD's building null). */
        double logUnrelated{0};
    };
    Evidence evidence(const Eigen::MatrixX3d& d, double nearRadius) const;
    /** The same from the differences already in the basis (Basis::toEigenbasis * d): the
     * differences are linear in both windows, so a window's projection can be kept and
     * reused against every query. */
    Evidence evidenceProjected(const Eigen::MatrixX3d& projectedD, double nearRadius) const;

    /** log p(d | delta) - log p(d | unrelated places). */
    double logLikelihoodRatio(const Eigen::MatrixX3d& d, double delta) const;
    /** d' C(delta)^-1 d summed over the components. */
    double chi2(const Eigen::MatrixX3d& d, double delta) const;
    /** A lower bound of chi2(d, delta) from d' C1^-1 d alone (the eigenvalues' largest):
     * candidates can be ruled out before their differences are formed. */
    double chi2LowerBound(double whiteChi2, double delta) const;

  private:
    /** The differences in the basis where C(delta) is diagonal, squared and summed over the
     * components (one value per eigenvalue). */
    Eigen::VectorXd projected(const Eigen::MatrixX3d& d) const;
    double amplitude(double delta) const;  ///< 2 sigmaF^2 (1 - exp(-delta^2 / 2 l^2))
    /** 1 / (1 + amplitude(delta) eigenvalue), per eigenvalue. */
    Eigen::VectorXd inverseFactors(double delta) const;
    /** -1/2 of the log-determinant's part that depends on delta (three components). */
    double logDeterminantTerm(double delta) const;
    double logRatio(const Eigen::VectorXd& p2, double delta) const;

    std::shared_ptr<const Basis> basis_;
    double sigma_f2_{0}, unrelated_sigma_f2_{0}, radius_{1};
    // The prior's bins: columns of inverse factors at each bin's middle (then unrelated
    // places), and per bin log(mass) + its log-determinant term.
    int bins_{0}, near_bins_{10};
    Eigen::MatrixXd bin_factors_;
    Eigen::VectorXd bin_log_constants_, bin_delta2_;
    double unrelated_log_determinant_{0};
};

}  // namespace lodestone::magnetic
