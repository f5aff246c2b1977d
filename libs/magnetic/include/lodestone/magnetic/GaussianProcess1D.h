#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <vector>

namespace lodestone::magnetic {

/** Hyperparameters of the field-along-the-path GP: k(a, b) = sigma_c^2 + sigma_f^2
 * exp(-(a - b)^2 / (2 l^2)), observations with noise sigma_n. sigma_c is the constant term for
 * what is common to a whole stretch (the earth field, a sensor bias). */
struct GpHyperparameters {
    double sigmaF{4.0};       ///< anomaly amplitude [uT]
    double lengthScale{0.3};  ///< correlation length along the path [m]
    double sigmaN{0.5};       ///< reading noise [uT]
    double sigmaC{10.0};      ///< constant term [uT]

    bool valid() const { return sigmaF > 0 && lengthScale > 0 && sigmaN > 0 && sigmaC >= 0; }
};

/** Gaussian-process regression of several field channels over one input, the travel along the
 * path [m] (paper 000 eq. 3 fits one to the target bundle's field). The channels share the
 * kernel; each has its own mean, removed before the fit. */
class GaussianProcess1D {
  public:
    explicit GaussianProcess1D(const GpHyperparameters& h);

    /** Conditions on readings `Y` (n x channels) at inputs `x` (n). Throws
     * std::invalid_argument on size mismatch or an empty set. */
    void fit(const std::vector<double>& x, const Eigen::MatrixXd& Y);
    /** Predictive mean (m x channels) and variance of a new reading (latent + noise, m) at
     * `xs`. */
    void predict(const std::vector<double>& xs, Eigen::MatrixXd& mean,
                 Eigen::VectorXd& variance) const;
    /** Sum over points and channels of log N(y; mean, variance): how well readings `Y` at `xs`
     * fit the GP. */
    double logLikelihood(const std::vector<double>& xs, const Eigen::MatrixXd& Y) const;

    /** Log marginal likelihood of `Y` at `x` (each channel mean-removed), summed over the
     * channels, and optionally its gradient with respect to (log sigma_f, log l, log sigma_n,
     * log sigma_c). */
    static double logMarginal(const std::vector<double>& x, const Eigen::MatrixXd& Y,
                              const GpHyperparameters& h, Eigen::Vector4d* gradient = nullptr);

    const GpHyperparameters& hyperparameters() const { return h_; }

  private:
    GpHyperparameters h_;
    std::vector<double> x_;
    Eigen::RowVectorXd mean_;
    Eigen::MatrixXd alpha_;  // K^-1 (Y - mean)
    Eigen::LLT<Eigen::MatrixXd> llt_;
};

}  // namespace lodestone::magnetic
