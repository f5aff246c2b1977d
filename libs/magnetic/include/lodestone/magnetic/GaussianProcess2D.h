#pragma once

#include <lodestone/magnetic/GaussianProcess1D.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace lodestone::magnetic {

/** Gaussian-process regression of several field channels over the floor plane (x, y) [m], with
 * the same squared-exponential + constant kernel as the along-the-path GP (GpHyperparameters:
 * the length scale is then isotropic in the plane). Where the robot passed a place more than
 * once, slightly apart, it learns how the field changes across the path too, which a 1-D GP
 * over travel cannot. */
class GaussianProcess2D {
  public:
    explicit GaussianProcess2D(const GpHyperparameters& h);

    /** Conditions on readings `Y` (n x channels) at `points` (n x 2). Throws
     * std::invalid_argument on size mismatch or an empty set. */
    void fit(const Eigen::MatrixX2d& points, const Eigen::MatrixXd& Y);
    /** Predictive mean at `p` (channels) and, if asked, its gradient (channels x 2). */
    Eigen::VectorXd mean(const Eigen::Vector2d& p, Eigen::MatrixX2d* gradient = nullptr) const;
    /** Predictive variance of a new reading at `p` (latent + noise). */
    double variance(const Eigen::Vector2d& p) const;
    /** The same at each row of `points` (m x 2), solved together (much faster than one by one). */
    Eigen::VectorXd variances(const Eigen::MatrixX2d& points) const;

    /** The readings `Y` (m x channels) at `points` (m x 2) judged together, their correlation
     * given the data included: log p(Y | data), the channels independent. With `information`,
     * also the Fisher information of a rigid move of the points (dx, dy, dyaw about `pivot`)
     * under that same joint covariance - readings a few centimetres apart are not independent
     * evidence, which a sum over readings would pretend. */
    double jointLogLikelihood(const Eigen::MatrixX2d& points, const Eigen::MatrixXd& Y,
                              const Eigen::Vector2d& pivot = Eigen::Vector2d::Zero(),
                              Eigen::Matrix3d* information = nullptr) const;
    /** log p(Y) under the prior alone (mean: the data's; no data near): what the readings are
     * worth when the map says nothing of them - the null hypothesis of a map match. */
    double priorLogLikelihood(const Eigen::MatrixX2d& points, const Eigen::MatrixXd& Y) const;

    const GpHyperparameters& hyperparameters() const { return h_; }
    Eigen::Index size() const { return points_.rows(); }

  private:
    /** Prior covariance among `a`'s rows (m x m), reading noise on the diagonal. */
    Eigen::MatrixXd priorCovariance(const Eigen::MatrixX2d& a) const;
    /** Gaussian log density of each column of `r` under covariance `S` (shared), summed. */
    static double gaussianLogDensity(const Eigen::MatrixXd& r, const Eigen::LLT<Eigen::MatrixXd>& S);

    GpHyperparameters h_;
    Eigen::MatrixX2d points_;
    Eigen::RowVectorXd mean_;
    Eigen::MatrixXd alpha_;  // K^-1 (Y - mean)
    Eigen::LLT<Eigen::MatrixXd> llt_;
};

}  // namespace lodestone::magnetic
