#include <lodestone/magnetic/GaussianProcess2D.h>

#include <cmath>
#include <stdexcept>

namespace lodestone::magnetic {

GaussianProcess2D::GaussianProcess2D(const GpHyperparameters& h) : h_(h) {
    if (!h.valid()) throw std::invalid_argument("GaussianProcess2D: hyperparameters must be > 0");
}

void GaussianProcess2D::fit(const Eigen::MatrixX2d& points, const Eigen::MatrixXd& Y) {
    if (points.rows() == 0 || points.rows() != Y.rows())
        throw std::invalid_argument("GaussianProcess2D::fit: empty or mismatched inputs");
    points_ = points;
    mean_ = Y.colwise().mean();
    const Eigen::Index n = points.rows();
    const double f2 = h_.sigmaF * h_.sigmaF, c2 = h_.sigmaC * h_.sigmaC,
                 inv2l2 = 0.5 / (h_.lengthScale * h_.lengthScale);
    Eigen::MatrixXd K(n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
        for (Eigen::Index j = 0; j <= i; ++j) {
            const double v = c2 + f2 * std::exp(-(points.row(i) - points.row(j)).squaredNorm() * inv2l2);
            K(i, j) = K(j, i) = v;
        }
        K(i, i) += h_.sigmaN * h_.sigmaN;
    }
    llt_.compute(K);
    alpha_ = llt_.solve(Y.rowwise() - mean_);
}

Eigen::VectorXd GaussianProcess2D::mean(const Eigen::Vector2d& p, Eigen::MatrixX2d* gradient) const {
    const double f2 = h_.sigmaF * h_.sigmaF, c2 = h_.sigmaC * h_.sigmaC,
                 il2 = 1.0 / (h_.lengthScale * h_.lengthScale);
    Eigen::VectorXd m = mean_.transpose();
    if (gradient) gradient->setZero(alpha_.cols(), 2);
    // The constant term sums once; the SE term only within 4 length scales (beyond, it is
    // below e^-8 of sigma_f^2: most of a 3 m stretch's readings are that far from any point).
    m += c2 * alpha_.colwise().sum().transpose();
    const double cutoff = 16.0 / il2;
    for (Eigen::Index j = 0; j < points_.rows(); ++j) {
        const Eigen::Vector2d d = p - points_.row(j).transpose();
        const double d2 = d.squaredNorm();
        if (d2 > cutoff) continue;
        const double se = f2 * std::exp(-0.5 * d2 * il2);
        m += se * alpha_.row(j).transpose();
        if (gradient) *gradient -= alpha_.row(j).transpose() * (se * il2 * d.transpose());
    }
    return m;
}

double GaussianProcess2D::variance(const Eigen::Vector2d& p) const {
    return variances(p.transpose())[0];
}

Eigen::VectorXd GaussianProcess2D::variances(const Eigen::MatrixX2d& at) const {
    const double f2 = h_.sigmaF * h_.sigmaF, c2 = h_.sigmaC * h_.sigmaC,
                 inv2l2 = 0.5 / (h_.lengthScale * h_.lengthScale);
    Eigen::MatrixXd k(points_.rows(), at.rows());
    for (Eigen::Index i = 0; i < at.rows(); ++i)
        for (Eigen::Index j = 0; j < points_.rows(); ++j)
            k(j, i) = c2 + f2 * std::exp(-(at.row(i) - points_.row(j)).squaredNorm() * inv2l2);
    // k^T K^-1 k = |L^-1 k|^2, all columns in one triangular solve.
    const Eigen::MatrixXd v = llt_.matrixL().solve(k);
    Eigen::VectorXd var(at.rows());
    for (Eigen::Index i = 0; i < at.rows(); ++i)
        var[i] = std::max(0.0, f2 + c2 - v.col(i).squaredNorm()) + h_.sigmaN * h_.sigmaN;
    return var;
}

}  // namespace lodestone::magnetic
