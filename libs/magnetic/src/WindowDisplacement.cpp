#include <lodestone/magnetic/WindowDisplacement.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lodestone::magnetic {

WindowDisplacementModel::Basis::Basis(std::size_t n, const PassNoise& noise, double lengthScale)
    : lengthScale(lengthScale) {
    if (n < 2 || !(lengthScale > 0))
        throw std::invalid_argument("WindowDisplacementModel: bad window or kernel");
    const auto m = static_cast<Eigen::Index>(n);
    Eigen::MatrixXd K(m, m);
    for (Eigen::Index i = 0; i < m; ++i) {
        for (Eigen::Index j = 0; j < m; ++j) {
            const double r = double(i - j) * noise.step / lengthScale;
            K(i, j) = std::exp(-0.5 * r * r);
        }
    }
    // C(delta) = L (I + a L^-1 K L^-T) L' = L U (I + a diag) U' L': one basis for every delta.
    const Eigen::LLT<Eigen::MatrixXd> llt(passNoiseCovariance(n, noise));
    const Eigen::MatrixXd Linv = llt.matrixL().solve(Eigen::MatrixXd::Identity(m, m));
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Linv * K * Linv.transpose());
    eigenvalues = eig.eigenvalues().cwiseMax(0.0);
    toEigenbasis = eig.eigenvectors().transpose() * Linv;
}

WindowDisplacementModel::WindowDisplacementModel(std::size_t n, const PassNoise& noise,
                                                 double sigmaF, double lengthScale,
                                                 double priorSigma, double radius)
    : WindowDisplacementModel(std::make_shared<Basis>(n, noise, lengthScale), sigmaF, priorSigma,
                              radius) {}

WindowDisplacementModel::WindowDisplacementModel(std::shared_ptr<const Basis> basis, double sigmaF,
                                                 double priorSigma, double radius,
                                                 double unrelatedSigmaF)
    : basis_(std::move(basis)),
      sigma_f2_(sigmaF * sigmaF),
      unrelated_sigma_f2_(std::isnan(unrelatedSigmaF) ? sigmaF * sigmaF
                                                      : unrelatedSigmaF * unrelatedSigmaF),
      radius_(radius) {
    if (!basis_ || !(sigmaF >= 0) || !(std::isnan(unrelatedSigmaF) || unrelatedSigmaF >= 0))
        throw std::invalid_argument("WindowDisplacementModel: no basis, or a negative amplitude");
    if (!(priorSigma > 0) || !(radius > 0))
        throw std::invalid_argument("WindowDisplacementModel: prior sigma and radius must be > 0");
    const auto m = basis_->eigenvalues.size();

    // The half-normal prior's bins of radius / 10, out to where its mass is gone; each bin's
    // likelihood taken at its middle. One more column: unrelated places.
    const double h = radius / near_bins_;
    bins_ = static_cast<int>(std::ceil(std::max(2 * radius, 6 * priorSigma) / h));
    const auto cdf = [&](double x) { return std::erf(x / (priorSigma * std::sqrt(2.0))); };
    bin_factors_.resize(m, bins_ + 1);
    bin_log_constants_.resize(bins_);
    bin_delta2_.resize(bins_);
    for (int k = 0; k < bins_; ++k) {
        const double delta = (k + 0.5) * h;
        const double mass = (k + 1 == bins_ ? 1.0 : cdf((k + 1) * h)) - cdf(k * h);
        bin_factors_.col(k) = inverseFactors(delta);
        bin_log_constants_[k] = (mass > 0 ? std::log(mass) : -INFINITY) + logDeterminantTerm(delta);
        bin_delta2_[k] = delta * delta;
    }
    bin_factors_.col(bins_) = inverseFactors(INFINITY);
    unrelated_log_determinant_ = logDeterminantTerm(INFINITY);
}

double WindowDisplacementModel::amplitude(double delta) const {
    if (std::isinf(delta)) return 2 * unrelated_sigma_f2_;
    const double r = delta / basis_->lengthScale;
    return 2 * sigma_f2_ * -std::expm1(-0.5 * r * r);
}

Eigen::VectorXd WindowDisplacementModel::inverseFactors(double delta) const {
    return (1.0 + amplitude(delta) * basis_->eigenvalues.array()).inverse().matrix();
}

double WindowDisplacementModel::logDeterminantTerm(double delta) const {
    // Three independent components; C1's determinant is common to every delta and left out.
    return -1.5 * (1.0 + amplitude(delta) * basis_->eigenvalues.array()).log().sum();
}

Eigen::VectorXd WindowDisplacementModel::projected(const Eigen::MatrixX3d& d) const {
    // (lazily: at this size the general product's packing costs more than the product)
    return basis_->toEigenbasis.lazyProduct(d).rowwise().squaredNorm();
}

double WindowDisplacementModel::logRatio(const Eigen::VectorXd& p2, double delta) const {
    const auto logLikelihood = [&](double x) {
        return -0.5 * p2.dot(inverseFactors(x)) + logDeterminantTerm(x);
    };
    return logLikelihood(delta) - logLikelihood(INFINITY);
}

double WindowDisplacementModel::logLikelihoodRatio(const Eigen::MatrixX3d& d, double delta) const {
    return logRatio(projected(d), delta);
}

double WindowDisplacementModel::chi2(const Eigen::MatrixX3d& d, double delta) const {
    return projected(d).dot(inverseFactors(delta));
}

double WindowDisplacementModel::chi2LowerBound(double whiteChi2, double delta) const {
    const double largest = basis_->eigenvalues.size() ? basis_->eigenvalues.maxCoeff() : 0.0;
    return whiteChi2 / (1.0 + amplitude(delta) * largest);
}

WindowDisplacementModel::Evidence WindowDisplacementModel::evidence(const Eigen::MatrixX3d& d,
                                                                    double nearRadius) const {
    return evidenceProjected(basis_->toEigenbasis.lazyProduct(d), nearRadius);
}

WindowDisplacementModel::Evidence WindowDisplacementModel::evidenceProjected(
    const Eigen::MatrixX3d& projectedD, double nearRadius) const {
    const int nearBins = std::clamp(
        static_cast<int>(std::floor(nearRadius / radius_ * near_bins_ + 1e-9)), 1, near_bins_);
    const double h = radius_ / near_bins_;
    // Every bin's quadratic form in one product.
    const Eigen::VectorXd p2 = projectedD.rowwise().squaredNorm();
    const Eigen::VectorXd q = bin_factors_.transpose() * p2;
    const double unrelated = -0.5 * q[bins_] + unrelated_log_determinant_;
    const Eigen::ArrayXd logTerms =
        bin_log_constants_.array() - 0.5 * q.head(bins_).array() - unrelated;
    const double nearMax = logTerms.head(nearBins).maxCoeff();
    const double farMax = logTerms.tail(bins_ - nearBins).maxCoeff();
    const Eigen::ArrayXd near = (logTerms.head(nearBins) - nearMax).exp();
    const double far = (logTerms.tail(bins_ - nearBins) - farMax).exp().sum();
    Evidence e;
    e.logNear = nearMax + std::log(near.sum());
    e.logFar = std::isfinite(farMax) ? farMax + std::log(far) : -INFINITY;
    e.nearDelta2 = (near * bin_delta2_.head(nearBins).array()).sum() / near.sum();
    e.chi2AtRadius = p2.dot(inverseFactors(nearBins * h));
    e.logUnrelated = unrelated;
    return e;
}

}  // namespace lodestone::magnetic
