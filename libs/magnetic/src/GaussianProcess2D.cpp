#include <lodestone/magnetic/GaussianProcess2D.h>

#include <cmath>
#include <limits>
#include <vector>
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

Eigen::MatrixXd GaussianProcess2D::priorCovariance(const Eigen::MatrixX2d& a) const {
    const double f2 = h_.sigmaF * h_.sigmaF, c2 = h_.sigmaC * h_.sigmaC,
                 inv2l2 = 0.5 / (h_.lengthScale * h_.lengthScale);
    const Eigen::Index m = a.rows();
    Eigen::MatrixXd K(m, m);
    for (Eigen::Index i = 0; i < m; ++i) {
        for (Eigen::Index j = 0; j <= i; ++j)
            K(i, j) = K(j, i) = c2 + f2 * std::exp(-(a.row(i) - a.row(j)).squaredNorm() * inv2l2);
        K(i, i) += h_.sigmaN * h_.sigmaN;
    }
    return K;
}

double GaussianProcess2D::gaussianLogDensity(const Eigen::MatrixXd& r,
                                             const Eigen::LLT<Eigen::MatrixXd>& S) {
    const Eigen::MatrixXd w = S.matrixL().solve(r);
    const double logDet = 2 * S.matrixLLT().diagonal().array().log().sum();
    return -0.5 * (w.squaredNorm() + double(r.cols()) * (logDet + double(r.rows()) * std::log(2 * M_PI)));
}

double GaussianProcess2D::priorLogLikelihood(const Eigen::MatrixX2d& at, const Eigen::MatrixXd& Y) const {
    if (at.rows() != Y.rows() || Y.cols() != mean_.cols())
        throw std::invalid_argument("GaussianProcess2D::priorLogLikelihood: mismatched inputs");
    const Eigen::LLT<Eigen::MatrixXd> S(priorCovariance(at));
    return gaussianLogDensity(Y.rowwise() - mean_, S);
}

double GaussianProcess2D::jointLogLikelihood(const Eigen::MatrixX2d& at, const Eigen::MatrixXd& Y,
                                             const Eigen::Vector2d& pivot,
                                             Eigen::Matrix3d* information) const {
    if (at.rows() != Y.rows() || Y.cols() != mean_.cols())
        throw std::invalid_argument("GaussianProcess2D::jointLogLikelihood: mismatched inputs");
    const double f2 = h_.sigmaF * h_.sigmaF, c2 = h_.sigmaC * h_.sigmaC,
                 inv2l2 = 0.5 / (h_.lengthScale * h_.lengthScale);
    const Eigen::Index m = at.rows(), n = points_.rows();
    Eigen::MatrixXd k(n, m);
    for (Eigen::Index i = 0; i < m; ++i)
        for (Eigen::Index j = 0; j < n; ++j)
            k(j, i) = c2 + f2 * std::exp(-(at.row(i) - points_.row(j)).squaredNorm() * inv2l2);
    const Eigen::MatrixXd v = llt_.matrixL().solve(k);
    const Eigen::LLT<Eigen::MatrixXd> S(priorCovariance(at) - v.transpose() * v);
    if (S.info() != Eigen::Success) return -std::numeric_limits<double>::infinity();
    const Eigen::MatrixXd mu = (k.transpose() * alpha_).rowwise() + mean_;
    const double ll = gaussianLogDensity(Y - mu, S);
    if (information) {
        // d(mean of reading i, channel c) / d(dx, dy, dyaw), stacked per channel: the
        // information is J^T S^-1 J summed over channels.
        Eigen::Matrix2d J90;
        J90 << 0, -1, 1, 0;
        const Eigen::Index C = mean_.cols();
        std::vector<Eigen::MatrixXd> J(static_cast<std::size_t>(C), Eigen::MatrixXd(m, 3));
        Eigen::MatrixX2d grad;
        for (Eigen::Index i = 0; i < m; ++i) {
            mean(at.row(i).transpose(), &grad);
            Eigen::Matrix<double, 2, 3> dp;
            dp << Eigen::Matrix2d::Identity(), J90 * (at.row(i).transpose() - pivot);
            const Eigen::MatrixXd g = grad * dp;  // channels x 3
            for (Eigen::Index c = 0; c < C; ++c) J[static_cast<std::size_t>(c)].row(i) = g.row(c);
        }
        information->setZero();
        for (const auto& Jc : J) {
            const Eigen::MatrixXd w = S.matrixL().solve(Jc);
            *information += w.transpose() * w;
        }
    }
    return ll;
}

}  // namespace lodestone::magnetic
