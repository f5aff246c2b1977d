#include <lodestone/magnetic/FieldParticleFilter.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <limits>
#include <stdexcept>

namespace lodestone::magnetic {

namespace {
/** a (+) b on SE(2) (b in a's frame), and the Jacobians of the result in a and in b. */
Eigen::Vector3d compose(const Eigen::Vector3d& a, const Eigen::Vector3d& b, Eigen::Matrix3d* Ja,
                        Eigen::Matrix3d* Jb) {
    const double c = std::cos(a.z()), s = std::sin(a.z());
    if (Ja) *Ja << 1, 0, -s * b.x() - c * b.y(), 0, 1, c * b.x() - s * b.y(), 0, 0, 1;
    if (Jb) *Jb << c, -s, 0, s, c, 0, 0, 0, 1;
    return {a.x() + c * b.x() - s * b.y(), a.y() + s * b.x() + c * b.y(), a.z() + b.z()};
}
}  // namespace

FieldParticleFilter::FieldParticleFilter(std::shared_ptr<const PlanarFieldGrid> map,
                                         const Params& p)
    : map_(std::move(map)), params_(p), rng_(p.seed) {
    if (!map_ || map_->cells() == 0)
        throw std::invalid_argument("FieldParticleFilter: an empty map");
    if (p.particles == 0 || !(p.passSigma >= 0) || !(p.updateSpacing >= 0))
        throw std::invalid_argument("FieldParticleFilter: particles > 0, sigmas and spacing >= 0");
    spacing_ = p.updateSpacing > 0 ? p.updateSpacing : map_->hyperparameters().lengthScale;
    converged_sigma_ =
        p.convergedSigma > 0 ? p.convergedSigma : 0.5 * map_->hyperparameters().lengthScale;
    reset();
}

void FieldParticleFilter::reset() {
    const Eigen::MatrixX2d centres = map_->cellCentres();
    const double half = 0.5 * map_->cellSize();
    std::uniform_int_distribution<Eigen::Index> cell(0, centres.rows() - 1);
    std::uniform_real_distribution<double> jitter(-half, half), heading(-M_PI, M_PI);
    const std::size_t n = params_.particles;
    x_.resize(n);
    y_.resize(n);
    yaw_.resize(n);
    logw_.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Index c = cell(rng_);
        x_[i] = centres(c, 0) + jitter(rng_);
        y_[i] = centres(c, 1) + jitter(rng_);
        yaw_[i] = heading(rng_);
    }
    travel_since_ = spacing_;  // the first reading weighs
    weighings_ = 0;
    pending_.setZero();
    pending_cov_.setZero();
    cloud_ = cloud();
}

void FieldParticleFilter::move(const Eigen::Vector3d& delta, const Eigen::Matrix3d& cov) {
    if (!delta.allFinite() || !cov.allFinite()) return;
    Eigen::Matrix3d Ja, Jb;
    pending_ = compose(pending_, delta, &Ja, &Jb);
    pending_cov_ = Ja * pending_cov_ * Ja.transpose() + Jb * cov * Jb.transpose();
    travel_since_ += delta.head<2>().norm();
}

void FieldParticleFilter::applyMotion() {
    const Eigen::LLT<Eigen::Matrix3d> llt(pending_cov_);
    const Eigen::Matrix3d L =
        llt.info() == Eigen::Success ? Eigen::Matrix3d(llt.matrixL()) : Eigen::Matrix3d::Zero();
    std::normal_distribution<double> gauss(0.0, 1.0);
    for (std::size_t i = 0; i < x_.size(); ++i) {
        const Eigen::Vector3d d =
            pending_ + L * Eigen::Vector3d(gauss(rng_), gauss(rng_), gauss(rng_));
        const Eigen::Vector3d p = compose({x_[i], y_[i], yaw_[i]}, d, nullptr, nullptr);
        x_[i] = p.x();
        y_[i] = p.y();
        yaw_[i] = std::remainder(p.z(), 2 * M_PI);
    }
    pending_.setZero();
    pending_cov_.setZero();
}

bool FieldParticleFilter::measure(const Eigen::Vector3d& robotField) {
    if (!robotField.allFinite() || travel_since_ < spacing_) return false;
    travel_since_ = 0;
    applyMotion();
    const double noise = map_->hyperparameters().sigmaN * map_->hyperparameters().sigmaN +
                         params_.passSigma * params_.passSigma;
    if (log_variance_.empty()) {
        // Per cell (the last entry: off the band) the residual's variance and its log: the
        // weighing's cost is then a lookup, a turn and a log per particle.
        log_variance_.resize(map_->cells() + 1);
        variance_.resize(map_->cells() + 1);
        for (std::size_t k = 0; k <= map_->cells(); ++k) {
            const auto m = map_->cellPrediction(k < map_->cells() ? std::int64_t(k) : -1);
            variance_[k] = m.variance + noise;
            log_variance_[k] = std::log(variance_[k]);
        }
    }
    const double nu = params_.tailDof;
    double best = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < x_.size(); ++i) {
        const std::int64_t cell = map_->cellIndex(x_[i], y_[i]);
        const auto m = map_->cellPrediction(cell);
        const std::size_t k = cell < 0 ? map_->cells() : static_cast<std::size_t>(cell);
        const double c = std::cos(yaw_[i]), s = std::sin(yaw_[i]);
        const Eigen::Vector3d world(c * robotField.x() - s * robotField.y(),
                                    s * robotField.x() + c * robotField.y(), robotField.z());
        const double v = variance_[k];
        const double r2 = (world - m.mean.cast<double>()).squaredNorm();
        logw_[i] += nu > 0
                        ? -0.5 * ((nu + 3.0) * std::log1p(r2 / (nu * v)) + 3.0 * log_variance_[k])
                        : -0.5 * (r2 / v + 3.0 * log_variance_[k]);
        best = std::max(best, logw_[i]);
    }
    for (double& w : logw_) w -= best;
    ++weighings_;
    cloud_ = cloud();
    if (cloud_.effectiveShare < params_.resampleShare) {
        const std::size_t tracking = params_.trackingParticles > 0
                                         ? params_.trackingParticles
                                         : std::max<std::size_t>(1, params_.particles / 20);
        resample(cloud_.converged ? std::min(tracking, params_.particles) : params_.particles);
    }
    return true;
}

void FieldParticleFilter::resample(std::size_t n) {
    const std::size_t m = x_.size();
    std::vector<double> cumulative(m);
    double sum = 0;
    for (std::size_t i = 0; i < m; ++i) cumulative[i] = (sum += std::exp(logw_[i]));
    std::uniform_real_distribution<double> start(0.0, 1.0);
    const double u0 = start(rng_);
    std::vector<double> x(n), y(n), yaw(n);
    std::size_t j = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double u = (u0 + static_cast<double>(i)) / static_cast<double>(n) * sum;
        while (j + 1 < m && cumulative[j] < u) ++j;
        x[i] = x_[j];
        y[i] = y_[j];
        yaw[i] = yaw_[j];
    }
    // Copies of one particle would stay copies where the odometry is nearly exact: each is
    // jittered by half a grid cell, the map's resolution. Not in heading: the odometry's own
    // heading noise spreads it, and a jitter there would add up at every resampling.
    std::normal_distribution<double> jitter(0.0, 0.5 * map_->cellSize());
    for (std::size_t i = 0; i < n; ++i) {
        x[i] += jitter(rng_);
        y[i] += jitter(rng_);
    }
    x_.swap(x);
    y_.swap(y);
    yaw_.swap(yaw);
    logw_.assign(n, 0.0);
}

FieldParticleFilter::Estimate FieldParticleFilter::estimate() const {
    Estimate e = cloud_;
    Eigen::Matrix3d Ja, Jb;
    e.pose = compose(cloud_.pose, pending_, &Ja, &Jb);
    e.pose.z() = std::remainder(e.pose.z(), 2 * M_PI);
    e.covariance = Ja * cloud_.covariance * Ja.transpose() + Jb * pending_cov_ * Jb.transpose();
    return e;
}

FieldParticleFilter::Estimate FieldParticleFilter::cloud() const {
    Estimate e;
    double sum = 0, sum2 = 0, sx = 0, sy = 0, sc = 0, ss = 0;
    std::vector<double> weight(x_.size());
    for (std::size_t i = 0; i < x_.size(); ++i) {
        const double w = weight[i] = std::exp(logw_[i]);
        sum += w;
        sum2 += w * w;
        sx += w * x_[i];
        sy += w * y_[i];
        sc += w * std::cos(yaw_[i]);
        ss += w * std::sin(yaw_[i]);
    }
    e.pose = Eigen::Vector3d(sx / sum, sy / sum, std::atan2(ss, sc));
    e.effectiveShare = sum * sum / sum2 / static_cast<double>(x_.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < x_.size(); ++i) {
        const double w = weight[i] / sum;
        const Eigen::Vector3d d(x_[i] - e.pose.x(), y_[i] - e.pose.y(),
                                std::remainder(yaw_[i] - e.pose.z(), 2 * M_PI));
        cov += w * d * d.transpose();
    }
    e.covariance = cov;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> position(cov.topLeftCorner<2, 2>());
    e.converged = weighings_ > 0 &&
                  std::sqrt(std::max(0.0, position.eigenvalues().maxCoeff())) < converged_sigma_ &&
                  std::sqrt(cov(2, 2)) < params_.convergedYawSigma;
    return e;
}

}  // namespace lodestone::magnetic
