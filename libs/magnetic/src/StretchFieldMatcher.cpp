#include <lodestone/magnetic/StretchFieldMatcher.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <limits>
#include <stdexcept>

namespace lodestone::magnetic {

namespace {

constexpr std::size_t kNullPlaces = 128;

/** The stretch scored against the map at anchor poses, one heading at a time. */
class Scorer {
  public:
    Scorer(const PlanarFieldGrid& map, const std::vector<StretchSample>& stretch,
           const StretchMatchParams& p)
        : map_(map), stretch_(stretch), nu_(p.tailDof) {
        const auto& h = map.hyperparameters();
        const double noise = h.sigmaN * h.sigmaN + p.passSigma * p.passSigma;
        variance_.resize(map.cells());
        log_variance_.resize(map.cells());
        for (std::size_t k = 0; k < map.cells(); ++k) {
            variance_[k] = map.cellPrediction(std::int64_t(k)).variance + noise;
            log_variance_[k] = std::log(variance_[k]);
        }
        // The null's places: up to kNullPlaces cells spread evenly over the map.
        const std::size_t stride = std::max<std::size_t>(1, map.cells() / kNullPlaces);
        for (std::size_t k = 0; k < map.cells(); k += stride) null_places_.push_back(k);
        offset_.resize(stretch.size());
        world_.resize(stretch.size());
        null_.resize(stretch.size());
    }

    /** Turns the stretch to the anchor heading `yaw`. */
    void setHeading(double yaw) {
        for (std::size_t i = 0; i < stretch_.size(); ++i) {
            const auto& s = stretch_[i];
            offset_[i] = Eigen::Rotation2Dd(yaw) * s.pose.head<2>();
            const double c = std::cos(yaw + s.pose.z()), sn = std::sin(yaw + s.pose.z());
            world_[i] = {c * s.field.x() - sn * s.field.y(), sn * s.field.x() + c * s.field.y(),
                         s.field.z()};
            // The reading at a place of the map drawn at random: a mixture over its cells.
            double best = -std::numeric_limits<double>::infinity(), sum = 0;
            terms_.clear();
            for (const std::size_t k : null_places_) {
                const double r2 =
                    (world_[i] - map_.cellPrediction(std::int64_t(k)).mean.cast<double>())
                        .squaredNorm();
                terms_.push_back(logDensity(r2, variance_[k], log_variance_[k]));
                best = std::max(best, terms_.back());
            }
            for (const double t : terms_) sum += std::exp(t - best);
            null_[i] = best + std::log(sum / double(terms_.size()));
        }
    }

    /** Sum of the weighted log likelihood ratios with the anchor at (x, y); `support` gets the
     * weight of the samples on the band. */
    double score(double x, double y, double* support = nullptr, double* fit = nullptr) const {
        double sum = 0, on = 0, chi2 = 0;
        for (std::size_t i = 0; i < stretch_.size(); ++i) {
            const std::int64_t cell = map_.cellIndex(x + offset_[i].x(), y + offset_[i].y());
            if (cell < 0) continue;  // off the band: the prior either way
            const auto k = static_cast<std::size_t>(cell);
            const double r2 =
                (world_[i] - map_.cellPrediction(cell).mean.cast<double>()).squaredNorm();
            sum += stretch_[i].weight * (logDensity(r2, variance_[k], log_variance_[k]) - null_[i]);
            on += stretch_[i].weight;
            chi2 += stretch_[i].weight * r2 / variance_[k];
        }
        if (support) *support = on;
        if (fit) *fit = chi2;
        return sum;
    }

  private:
    /** log density of a 3-vector residual of squared norm r2, up to a constant shared by all. */
    double logDensity(double r2, double v, double logV) const {
        return nu_ > 0 ? -0.5 * ((nu_ + 3.0) * std::log1p(r2 / (nu_ * v)) + 3.0 * logV)
                       : -0.5 * (r2 / v + 3.0 * logV);
    }

    const PlanarFieldGrid& map_;
    const std::vector<StretchSample>& stretch_;
    double nu_;
    std::vector<double> variance_, log_variance_;
    std::vector<std::size_t> null_places_;
    std::vector<double> terms_;
    std::vector<Eigen::Vector2d> offset_;
    std::vector<Eigen::Vector3d> world_;
    std::vector<double> null_;
};

struct Candidate {
    Eigen::Vector3d delta;  ///< from the prior pose
    double logPosterior;    ///< unnormalized
};

/** Weighted mean and covariance of the candidates (weights exp(logPosterior - max)). */
void moments(const std::vector<Candidate>& c, Eigen::Vector3d& mean, Eigen::Matrix3d& cov) {
    double best = -std::numeric_limits<double>::infinity();
    for (const auto& k : c) best = std::max(best, k.logPosterior);
    double sum = 0;
    mean.setZero();
    for (const auto& k : c) {
        const double w = std::exp(k.logPosterior - best);
        sum += w;
        mean += w * k.delta;
    }
    mean /= sum;
    cov.setZero();
    for (const auto& k : c) {
        const Eigen::Vector3d d = k.delta - mean;
        cov += std::exp(k.logPosterior - best) / sum * d * d.transpose();
    }
}

}  // namespace

StretchMatch matchStretch(const PlanarFieldGrid& map, const std::vector<StretchSample>& stretch,
                          const Eigen::Vector3d& priorPose, const Eigen::Matrix2d& priorCovariance,
                          const StretchMatchParams& p) {
    if (!(p.step > 0 && p.yawStep > 0 && p.fineStep > 0 && p.fineYawStep > 0 && p.maxOffset >= 0 &&
          p.maxYaw >= 0))
        throw std::invalid_argument("matchStretch: steps > 0, ranges >= 0");
    StretchMatch out;
    if (stretch.empty() || map.cells() == 0 || !priorPose.allFinite() ||
        !priorCovariance.allFinite())
        return out;
    Scorer scorer(map, stretch, p);
    const Eigen::Matrix2d information = priorCovariance.inverse();
    const auto logPrior = [&](const Eigen::Vector2d& d) { return -0.5 * d.dot(information * d); };
    // The gate: three sigmas of the prior per axis, at most maxOffset.
    const int nx =
        static_cast<int>(std::min(3 * std::sqrt(priorCovariance(0, 0)), p.maxOffset) / p.step);
    const int ny =
        static_cast<int>(std::min(3 * std::sqrt(priorCovariance(1, 1)), p.maxOffset) / p.step);
    const int nyaw = static_cast<int>(p.maxYaw / p.yawStep);
    const auto logAdd = [](double a, double b) {
        if (a < b) std::swap(a, b);
        return b == -std::numeric_limits<double>::infinity() ? a : a + std::log1p(std::exp(b - a));
    };
    double priorMass = -std::numeric_limits<double>::infinity();
    for (int i = -nx; i <= nx; ++i)
        for (int j = -ny; j <= ny; ++j)
            priorMass = logAdd(priorMass, logPrior({i * p.step, j * p.step}));
    // The search grid about the prior, the stretch turned by `turn` more; its evidence (the
    // likelihood ratio averaged over the prior, flat in heading).
    std::vector<Candidate> grid;
    const auto search = [&](double turn) {
        grid.clear();
        for (int k = -nyaw; k <= nyaw; ++k) {
            scorer.setHeading(priorPose.z() + turn + k * p.yawStep);
            for (int i = -nx; i <= nx; ++i)
                for (int j = -ny; j <= ny; ++j) {
                    const Eigen::Vector2d d(i * p.step, j * p.step);
                    grid.push_back(
                        {{d.x(), d.y(), k * p.yawStep},
                         logPrior(d) + scorer.score(priorPose.x() + d.x(), priorPose.y() + d.y())});
                }
        }
        double total = -std::numeric_limits<double>::infinity();
        for (const auto& c : grid) total = logAdd(total, c.logPosterior);
        return total - priorMass - std::log(2.0 * nyaw + 1.0);
    };
    out.logEvidence = search(0);
    out.candidates = grid.size();
    Eigen::Vector3d mean;
    Eigen::Matrix3d cov;
    moments(grid, mean, cov);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> spread(cov.topLeftCorner<2, 2>());
    out.positionSigma = std::sqrt(std::max(0.0, spread.eigenvalues().maxCoeff()));
    out.yawSigma = std::sqrt(std::max(0.0, cov(2, 2)));
    // Refined around the best cell: its mean; the covariance the coarse grid's plus what its
    // steps hide (a step^2 / 12 each).
    const auto best = std::max_element(grid.begin(), grid.end(), [](const auto& a, const auto& b) {
                          return a.logPosterior < b.logPosterior;
                      })->delta;
    std::vector<Candidate> fine;
    const int fx = static_cast<int>(std::round(p.step / p.fineStep));
    const int fyaw = static_cast<int>(std::round(p.yawStep / p.fineYawStep));
    for (int k = -fyaw; k <= fyaw; ++k) {
        const double yaw = best.z() + k * p.fineYawStep;
        scorer.setHeading(priorPose.z() + yaw);
        for (int i = -fx; i <= fx; ++i)
            for (int j = -fx; j <= fx; ++j) {
                const Eigen::Vector2d d(best.x() + i * p.fineStep, best.y() + j * p.fineStep);
                fine.push_back(
                    {{d.x(), d.y(), yaw},
                     logPrior(d) + scorer.score(priorPose.x() + d.x(), priorPose.y() + d.y())});
            }
    }
    Eigen::Matrix3d fineCov;
    moments(fine, mean, fineCov);
    out.pose = priorPose + mean;
    out.covariance = cov;
    out.covariance(0, 0) += p.step * p.step / 12;
    out.covariance(1, 1) += p.step * p.step / 12;
    out.covariance(2, 2) += p.yawStep * p.yawStep / 12;
    scorer.setHeading(out.pose.z());
    scorer.score(out.pose.x(), out.pose.y(), &out.support, &out.fit);
    return out;
}

}  // namespace lodestone::magnetic
