#include <lodestone/magnetic/GaussianProcess1D.h>

#include <cmath>
#include <stdexcept>

namespace lodestone::magnetic {

namespace {
double kernel(double a, double b, const GpHyperparameters& h) {
    const double d = (a - b) / h.lengthScale;
    return h.sigmaC * h.sigmaC + h.sigmaF * h.sigmaF * std::exp(-0.5 * d * d);
}

Eigen::MatrixXd covariance(const std::vector<double>& x, const GpHyperparameters& h) {
    const auto n = static_cast<Eigen::Index>(x.size());
    Eigen::MatrixXd K(n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
        for (Eigen::Index j = 0; j <= i; ++j) K(i, j) = K(j, i) = kernel(x[i], x[j], h);
        K(i, i) += h.sigmaN * h.sigmaN;
    }
    return K;
}
}  // namespace

GaussianProcess1D::GaussianProcess1D(const GpHyperparameters& h) : h_(h) {
    if (!h.valid()) throw std::invalid_argument("GaussianProcess1D: hyperparameters must be > 0");
}

void GaussianProcess1D::fit(const std::vector<double>& x, const Eigen::MatrixXd& Y) {
    if (x.empty() || Y.rows() != static_cast<Eigen::Index>(x.size())) {
        throw std::invalid_argument("GaussianProcess1D::fit: inputs and readings differ in number");
    }
    x_ = x;
    mean_ = Y.colwise().mean();
    llt_.compute(covariance(x, h_));
    alpha_ = llt_.solve(Y.rowwise() - mean_);
}

void GaussianProcess1D::predict(const std::vector<double>& xs, Eigen::MatrixXd& mean,
                                Eigen::VectorXd& variance) const {
    const auto m = static_cast<Eigen::Index>(xs.size());
    const auto n = static_cast<Eigen::Index>(x_.size());
    Eigen::MatrixXd Ks(n, m);
    for (Eigen::Index j = 0; j < m; ++j) {
        for (Eigen::Index i = 0; i < n; ++i) Ks(i, j) = kernel(x_[i], xs[j], h_);
    }
    mean = Ks.transpose() * alpha_;
    mean.rowwise() += mean_;
    const Eigen::MatrixXd v = llt_.matrixL().solve(Ks);
    const double prior = h_.sigmaC * h_.sigmaC + h_.sigmaF * h_.sigmaF + h_.sigmaN * h_.sigmaN;
    variance =
        (prior - v.colwise().squaredNorm().array()).max(h_.sigmaN * h_.sigmaN).matrix().transpose();
}

double GaussianProcess1D::logLikelihood(const std::vector<double>& xs,
                                        const Eigen::MatrixXd& Y) const {
    Eigen::MatrixXd mean;
    Eigen::VectorXd var;
    predict(xs, mean, var);
    const Eigen::MatrixXd r = Y - mean;
    double ll = 0;
    for (Eigen::Index i = 0; i < r.rows(); ++i) {
        ll -= 0.5 * (r.row(i).squaredNorm() / var[i] + r.cols() * std::log(2 * M_PI * var[i]));
    }
    return ll;
}

double GaussianProcess1D::logMarginal(const std::vector<double>& x, const Eigen::MatrixXd& Y,
                                      const GpHyperparameters& h, Eigen::Vector4d* gradient) {
    const auto n = static_cast<Eigen::Index>(x.size());
    const Eigen::MatrixXd Yc = Y.rowwise() - Y.colwise().mean();
    const Eigen::LLT<Eigen::MatrixXd> llt(covariance(x, h));
    if (llt.info() != Eigen::Success) return -std::numeric_limits<double>::infinity();
    const Eigen::MatrixXd alpha = llt.solve(Yc);
    const double logDet = 2 * llt.matrixLLT().diagonal().array().log().sum();
    const double C = static_cast<double>(Y.cols());
    const double value = -0.5 * (Yc.array() * alpha.array()).sum() - 0.5 * C * logDet -
                         0.5 * C * static_cast<double>(n) * std::log(2 * M_PI);
    if (gradient) {
        // dL/dtheta = 1/2 tr((sum_c a_c a_c^T - C K^-1) dK/dtheta)
        const Eigen::MatrixXd W =
            alpha * alpha.transpose() - C * llt.solve(Eigen::MatrixXd::Identity(n, n));
        double gF = 0, gL = 0, gC = 0;
        for (Eigen::Index i = 0; i < n; ++i) {
            for (Eigen::Index j = 0; j < n; ++j) {
                const double d2 = (x[i] - x[j]) * (x[i] - x[j]) / (h.lengthScale * h.lengthScale);
                const double e = h.sigmaF * h.sigmaF * std::exp(-0.5 * d2);
                gF += W(i, j) * 2 * e;
                gL += W(i, j) * e * d2;
                gC += W(i, j) * 2 * h.sigmaC * h.sigmaC;
            }
        }
        const double gN = W.trace() * 2 * h.sigmaN * h.sigmaN;
        *gradient = 0.5 * Eigen::Vector4d(gF, gL, gN, gC);
    }
    return value;
}

}  // namespace lodestone::magnetic
