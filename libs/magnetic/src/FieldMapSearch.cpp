#include <lodestone/magnetic/FieldMapSearch.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace lodestone::magnetic {

std::string toString(FieldMapVerdict v) {
    switch (v) {
        case FieldMapVerdict::Accepted: return "accepted";
        case FieldMapVerdict::NoFit: return "no fit";
        case FieldMapVerdict::NotAboveNull: return "not above the null";
        case FieldMapVerdict::Ambiguous: return "ambiguous";
        case FieldMapVerdict::TooLoose: return "too loose";
        case FieldMapVerdict::GateTooWide: return "gate too wide";
    }
    return "?";
}

namespace {

/** The map's predictive mean and variance on rasters over the region the stretch can be moved
 * to, read bilinearly: scoring hundreds of translations then costs lookups, not GP
 * evaluations. The variance changes over a length scale, not over readings: a coarser raster. */
class PredictiveRaster {
  public:
    PredictiveRaster(const GaussianProcess2D& gp, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                     double step)
        : mean_(lo, hi, step), variance_(lo, hi, 3 * step) {
        for (Eigen::Index k = 0; k < mean_.size(); ++k) mean_.values.push_back(gp.mean(mean_.point(k)));
        Eigen::MatrixX2d at(variance_.size(), 2);
        for (Eigen::Index k = 0; k < variance_.size(); ++k) at.row(k) = variance_.point(k).transpose();
        const Eigen::VectorXd v = gp.variances(at);
        for (Eigen::Index k = 0; k < variance_.size(); ++k)
            variance_.values.push_back(Eigen::VectorXd::Constant(1, v[k]));
    }
    Eigen::VectorXd mean(const Eigen::Vector2d& p) const { return mean_.at(p); }
    double variance(const Eigen::Vector2d& p) const { return variance_.at(p)[0]; }

  private:
    struct Lattice {
        Lattice(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double s) : origin(lo), step(s) {
            nx = static_cast<Eigen::Index>(std::ceil((hi.x() - lo.x()) / s)) + 2;
            ny = static_cast<Eigen::Index>(std::ceil((hi.y() - lo.y()) / s)) + 2;
        }
        Eigen::Index size() const { return nx * ny; }
        Eigen::Vector2d point(Eigen::Index k) const {
            return origin + step * Eigen::Vector2d(double(k % nx), double(k / nx));
        }
        Eigen::VectorXd at(const Eigen::Vector2d& p) const {
            const Eigen::Vector2d g = (p - origin) / step;
            const double fx = std::clamp(g.x(), 0.0, double(nx - 1) - 1e-9),
                         fy = std::clamp(g.y(), 0.0, double(ny - 1) - 1e-9);
            const auto i = static_cast<Eigen::Index>(fx), j = static_cast<Eigen::Index>(fy);
            const double a = fx - double(i), b = fy - double(j);
            return (1 - a) * (1 - b) * cell(i, j) + a * (1 - b) * cell(i + 1, j) +
                   (1 - a) * b * cell(i, j + 1) + a * b * cell(i + 1, j + 1);
        }
        const Eigen::VectorXd& cell(Eigen::Index i, Eigen::Index j) const {
            return values[static_cast<std::size_t>(j * nx + i)];
        }
        Eigen::Vector2d origin;
        double step;
        Eigen::Index nx{0}, ny{0};
        std::vector<Eigen::VectorXd> values;
    };
    Lattice mean_, variance_;
};

struct Optimum {
    Eigen::Vector3d x;  ///< dx, dy, dyaw about the stretch's centroid
    Eigen::Matrix3d covariance;
    double logLikelihood{0}, logPrior{0}, normalizedRms{0};
    bool onEdge{false};  ///< the fit still improves past the gate's edge
};

Eigen::MatrixX2d moved(const Eigen::MatrixX2d& points, const Eigen::Vector2d& pivot,
                       const Eigen::Vector3d& x) {
    const Eigen::Matrix2d R = Eigen::Rotation2Dd(x[2]).toRotationMatrix();
    Eigen::MatrixX2d out(points.rows(), 2);
    for (Eigen::Index i = 0; i < points.rows(); ++i)
        out.row(i) = (pivot + R * (points.row(i).transpose() - pivot) + x.head<2>()).transpose();
    return out;
}

/** One search: the stretch (`points`, `query`) against the map inside the gate, with what its
 * steps share - the pivot, the gate, the rasters. */
class Search {
  public:
    Search(const GaussianProcess2D& map, const Eigen::MatrixX2d& points, const Eigen::MatrixXd& query,
           const Eigen::Matrix2d& gateCovariance, const FieldMapSearchParams& params, double reach)
        : map_(map),
          points_(points),
          query_(query),
          params_(params),
          pivot_(points.colwise().mean().transpose()),
          gateInfo_(gateCovariance.inverse()),
          // The gate is the uncertainty of where the robot is now - the stretch's last point:
          // its move (the turn about the centroid included) is what must lie inside.
          lastArm_(points.row(points.rows() - 1).transpose() - pivot_),
          R_(reach),
          h_(params.gridStep),
          half_(static_cast<int>(std::floor(R_ / h_))),
          rasterStep_(std::min(h_, map.hyperparameters().lengthScale / 3)),
          raster_(map,
                  points.colwise().minCoeff().transpose() - Eigen::Vector2d::Constant(R_ + h_),
                  points.colwise().maxCoeff().transpose() + Eigen::Vector2d::Constant(R_ + h_),
                  rasterStep_),
          channels_(static_cast<double>(query.cols())),
          side_(2 * half_ + 1),
          grid_(static_cast<std::size_t>(side_ * side_), std::numeric_limits<double>::infinity()) {}

    const Eigen::Vector2d& pivot() const { return pivot_; }
    double rasterStep() const { return rasterStep_; }

    /** 1. Translations on a grid inside the gate, scored by the map's predictive density of
     * each reading (one by one: a ranking, not yet the verdict). Returns how many were tried. */
    std::size_t scoreGrid() {
        std::size_t tried = 0;
        for (int j = -half_; j <= half_; ++j) {
            for (int i = -half_; i <= half_; ++i) {
                const Eigen::Vector2d d(i * h_, j * h_);
                if (d.dot(gateInfo_ * d) > params_.gateChi2) continue;
                ++tried;
                cell(i, j) = score(Eigen::Vector3d(d.x(), d.y(), 0));
            }
        }
        return tried;
    }

    /** 2. The grid's local optima (no better neighbour), the best first, at most `refined`. */
    std::vector<std::pair<double, Eigen::Vector2d>> localOptima() {
        std::vector<std::pair<double, Eigen::Vector2d>> optima;
        for (int j = -half_; j <= half_; ++j) {
            for (int i = -half_; i <= half_; ++i) {
                const double s = cell(i, j);
                if (!std::isfinite(s)) continue;
                bool best = true;
                for (int dj = -1; dj <= 1 && best; ++dj)
                    for (int di = -1; di <= 1 && best; ++di) {
                        if ((di || dj) && std::abs(i + di) <= half_ && std::abs(j + dj) <= half_)
                            best = !(cell(i + di, j + dj) < s);
                    }
                if (best) optima.emplace_back(s, Eigen::Vector2d(i * h_, j * h_));
            }
        }
        std::sort(optima.begin(), optima.end(),
                  [](const auto& a, const auto& b) { return a.first < b.first; });
        if (optima.size() > params_.refined) optima.resize(params_.refined);
        return optima;
    }

    /** 3. One optimum refined (pattern search on the same density, the heading free within its
     * prior range - a gradient step on the mean alone would slide onto the earlier pass, where
     * the map is surest, rather than beside it, where the readings were taken), then judged by
     * the joint likelihood given the map. Nothing when it converged onto one already `kept`,
     * fits worse than the noise allows, or has no finite likelihood. */
    std::optional<Optimum> refine(double s0, const Eigen::Vector2d& d,
                                  const std::vector<Optimum>& kept) const {
        const double yawRange = 2 * params_.plane.priorSigmaYaw;
        Eigen::Vector3d x(d.x(), d.y(), 0);
        double best = s0;
        for (Eigen::Vector3d step(h_ / 2, h_ / 2, yawRange / 8); step[0] > 0.005; step /= 2) {
            for (bool moved = true; moved;) {
                moved = false;
                for (int axis = 0; axis < 3; ++axis) {
                    for (double sign : {-1.0, 1.0}) {
                        Eigen::Vector3d y = x;
                        y[axis] += sign * step[axis];
                        if ((y.head<2>() - d).norm() > params_.plane.maxShift ||
                            gate2(y) > params_.gateChi2 ||
                            std::abs(y[2]) > yawRange)
                            continue;
                        const double c = score(y);
                        if (c < best) {
                            best = c;
                            x = y;
                            moved = true;
                        }
                    }
                }
            }
        }
        Optimum o;
        o.x = x;
        // Held by the gate rather than by the field? Then the place may lie outside it.
        if (gate2(x) > 0.5 * params_.gateChi2) {
            Eigen::Vector3d out = x;
            out.head<2>() += h_ * lastMove(x).normalized();
            o.onEdge = score(out) < best;
        }
        const Eigen::Vector2d t = x.head<2>();
        if (std::any_of(kept.begin(), kept.end(), [&](const Optimum& k) {
                return (k.x.head<2>() - t).norm() < 0.5 * h_;  // converged to one already kept
            }))
            return std::nullopt;
        const Eigen::MatrixX2d at = moved(points_, pivot_, x);
        {
            const Eigen::VectorXd var = map_.variances(at);
            double sum = 0;
            for (Eigen::Index k = 0; k < at.rows(); ++k)
                sum += (query_.row(k).transpose() - map_.mean(at.row(k).transpose())).squaredNorm() / var[k];
            o.normalizedRms = std::sqrt(sum / double(query_.size()));
        }
        if (!(o.normalizedRms <= params_.maxNormalizedRms)) return std::nullopt;
        Eigen::Matrix3d info;
        o.logLikelihood = map_.jointLogLikelihood(at, query_, pivot_ + t, &info);
        o.logPrior = -0.5 * gate2(x);
        // The curvature under the readings' joint covariance, held weakly by the search region
        // and the heading prior where the field says nothing (a straight pass: along it);
        // a fit worse than the noise model makes it less sure.
        info.diagonal() += Eigen::Vector3d(1 / (R_ * R_), 1 / (R_ * R_),
                                           1 / (params_.plane.priorSigmaYaw * params_.plane.priorSigmaYaw));
        o.covariance = info.inverse() * std::max(1.0, o.normalizedRms * o.normalizedRms);
        if (!std::isfinite(o.logLikelihood)) return std::nullopt;
        return o;
    }

  private:
    Eigen::Vector2d lastMove(const Eigen::Vector3d& x) const {
        return x.head<2>() + Eigen::Rotation2Dd(x[2]).toRotationMatrix() * lastArm_ - lastArm_;
    }
    double gate2(const Eigen::Vector3d& x) const {
        const Eigen::Vector2d d = lastMove(x);
        return d.dot(gateInfo_ * d);
    }
    /** -2 log of each reading's predictive density (constants dropped), the stretch moved by x. */
    double score(const Eigen::Vector3d& x) const {
        const Eigen::Matrix2d Rx = Eigen::Rotation2Dd(x[2]).toRotationMatrix();
        double nll = 0;
        for (Eigen::Index k = 0; k < points_.rows(); ++k) {
            const Eigen::Vector2d p = pivot_ + Rx * (points_.row(k).transpose() - pivot_) + x.head<2>();
            const double var = raster_.variance(p);
            nll += (query_.row(k).transpose() - raster_.mean(p)).squaredNorm() / var + channels_ * std::log(var);
        }
        return nll;
    }
    double& cell(int i, int j) { return grid_[static_cast<std::size_t>((j + half_) * side_ + (i + half_))]; }

    const GaussianProcess2D& map_;
    const Eigen::MatrixX2d& points_;
    const Eigen::MatrixXd& query_;
    const FieldMapSearchParams& params_;
    const Eigen::Vector2d pivot_;
    const Eigen::Matrix2d gateInfo_;
    const Eigen::Vector2d lastArm_;
    const double R_, h_;
    const int half_;
    const double rasterStep_;
    const PredictiveRaster raster_;
    const double channels_;
    const int side_;
    std::vector<double> grid_;
};

/** 4.-7. The best optimum's place as a mixture of its optima, and the verdict on it. */
void judge(const std::vector<Optimum>& kept, const FieldMapSearchParams& params, double rasterStep,
           FieldMapMatch& result) {
    const double h = params.gridStep;
    const auto best = std::max_element(kept.begin(), kept.end(), [](const Optimum& a, const Optimum& b) {
        return a.logLikelihood + a.logPrior < b.logLikelihood + b.logPrior;
    });
    // (a fit worse than the noise model makes likelihood differences less telling)
    const double dispersion = std::max(1.0, best->normalizedRms * best->normalizedRms);
    result.logLikelihood = best->logLikelihood;
    result.alignment.normalizedRms = best->normalizedRms;
    const auto elsewhere = [&](const Optimum& o) {
        return (o.x.head<2>() - best->x.head<2>()).norm() > params.distinctRadius;
    };
    // 4. This place's optima as a mixture, weighted by likelihood and gate, moment-matched.
    const double top = best->logLikelihood + best->logPrior;
    double total = 0;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    std::vector<double> w;
    for (const auto& o : kept) {
        w.push_back(elsewhere(o) ? 0.0 : std::exp((o.logLikelihood + o.logPrior - top) / dispersion));
        total += w.back();
        mean += w.back() * o.x;
    }
    mean /= total;
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (std::size_t k = 0; k < kept.size(); ++k) {
        const Eigen::Vector3d e = kept[k].x - mean;
        cov += w[k] / total * (kept[k].covariance + e * e.transpose());
    }
    // The optimum was found on rasters: up to half a raster step off the exact one.
    const double floor2 = std::pow(std::max(params.plane.minSigma, rasterStep / 2), 2);
    for (int k = 0; k < 2; ++k) cov(k, k) += floor2;
    result.alignment.delta = mean;
    result.alignment.covariance = cov;
    result.alignment.valid = true;
    // 5. The evidence for "the map explains these readings somewhere in the region" over "it
    //    knows nothing of them": the likelihood ratio at the optimum times the Occam factor of
    //    having searched - the posterior's area over the region's (Laplace). Without it, the
    //    best of hundreds of tried places explains an unrelated field by e^10 now and then.
    const double region = double(result.hypotheses) * h * h;
    const double posteriorArea = 2 * M_PI * std::sqrt(cov.topLeftCorner<2, 2>().determinant());
    result.logEvidence = (best->logLikelihood - result.nullLogLikelihood) / dispersion +
                         std::log(std::min(1.0, posteriorArea / region));
    if (result.logEvidence < params.minLogRatio) {
        result.verdict = FieldMapVerdict::NotAboveNull;
        return;
    }
    // 6. Another place that fits about as well, or one beyond the gate's edge that might:
    //    no verdict between them.
    if (best->onEdge) {
        result.verdict = FieldMapVerdict::Ambiguous;
        return;
    }
    for (const auto& o : kept) {
        if (elsewhere(o) &&
            (best->logLikelihood - o.logLikelihood) / dispersion < params.ambiguityLogRatio) {
            result.verdict = FieldMapVerdict::Ambiguous;
            return;
        }
    }
    // 7. Too loose to say anything the gate did not.
    const double widest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(cov.topLeftCorner<2, 2>())
                              .eigenvalues()
                              .maxCoeff();
    result.verdict = std::sqrt(widest) > params.maxSigma ? FieldMapVerdict::TooLoose
                                                          : FieldMapVerdict::Accepted;
}

}  // namespace

double gateRadius(const Eigen::Matrix2d& gateCovariance, double gateChi2) {
    return std::sqrt(gateChi2 *
                     Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(gateCovariance).eigenvalues().maxCoeff());
}

FieldMapMatch searchFieldMap(const GaussianProcess2D& map, const Eigen::MatrixX2d& points,
                             const Eigen::MatrixXd& query, const Eigen::Matrix2d& gateCovariance,
                             const FieldMapSearchParams& params) {
    FieldMapMatch result;
    if (points.rows() < 3 || points.rows() != query.rows() || map.size() == 0) return result;
    const double reach = gateRadius(gateCovariance, params.gateChi2);
    if (!(reach <= params.maxRadius)) {
        result.verdict = FieldMapVerdict::GateTooWide;
        return result;
    }
    Search search(map, points, query, gateCovariance, params, reach);
    result.alignment.pivot = search.pivot();
    result.nullLogLikelihood = map.priorLogLikelihood(points, query);
    result.hypotheses = search.scoreGrid();
    std::vector<Optimum> kept;
    for (const auto& [s0, d] : search.localOptima()) {
        if (auto o = search.refine(s0, d, kept)) kept.push_back(*o);
    }
    result.optima = kept.size();
    if (kept.empty()) return result;
    judge(kept, params, search.rasterStep(), result);
    return result;
}

}  // namespace lodestone::magnetic
