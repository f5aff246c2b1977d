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

    const GpHyperparameters& hyperparameters() const { return h_; }
    Eigen::Index size() const { return points_.rows(); }

  private:
    GpHyperparameters h_;
    Eigen::MatrixX2d points_;
    Eigen::RowVectorXd mean_;
    Eigen::MatrixXd alpha_;  // K^-1 (Y - mean)
    Eigen::LLT<Eigen::MatrixXd> llt_;
};

}  // namespace lodestone::magnetic
