#include <lodestone/magnetic/PlanarAlignment.h>

#include <Eigen/Dense>
#include <cmath>

namespace lodestone::magnetic {

namespace {
Eigen::Matrix2d rotation(double a) {
    Eigen::Matrix2d R;
    R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    return R;
}

/** Residuals of the readings in predictive sigmas (fixed per point), and their Jacobian with
 * respect to (dx, dy, dyaw); returns the sum of squares including the prior. */
double evaluate(const GaussianProcess2D& gp, const Eigen::MatrixX2d& points,
                const Eigen::MatrixXd& query, const Eigen::VectorXd& sigma,
                const Eigen::Vector2d& pivot, const Eigen::Vector3d& x,
                const Eigen::Vector3d& priorInfo, Eigen::Matrix3d* H, Eigen::Vector3d* g) {
    const Eigen::Matrix2d R = rotation(x[2]);
    Eigen::Matrix2d J90;
    J90 << 0, -1, 1, 0;
    double cost = 0;
    if (H) H->setZero();
    if (g) g->setZero();
    Eigen::MatrixX2d grad;
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
        const Eigen::Vector2d arm = R * (points.row(i).transpose() - pivot);
        const Eigen::Vector2d p = pivot + arm + x.head<2>();
        const Eigen::VectorXd r = (query.row(i).transpose() - gp.mean(p, H ? &grad : nullptr)) / sigma[i];
        cost += r.squaredNorm();
        if (H) {
            Eigen::Matrix<double, 2, 3> dp;
            dp << Eigen::Matrix2d::Identity(), J90 * arm;
            const Eigen::MatrixXd J = -(grad * dp) / sigma[i];  // channels x 3
            *H += J.transpose() * J;
            *g += J.transpose() * r;
        }
    }
    cost += x.cwiseProduct(priorInfo).dot(x);
    if (H) H->diagonal() += priorInfo;
    if (g) *g += priorInfo.cwiseProduct(x);
    return cost;
}

double normalizedRms(const GaussianProcess2D& gp, const Eigen::MatrixX2d& points,
                     const Eigen::MatrixXd& query, const PlanarAlignmentResult& r) {
    Eigen::MatrixX2d moved(points.rows(), 2);
    for (Eigen::Index i = 0; i < points.rows(); ++i)
        moved.row(i) = r.apply(points.row(i).transpose()).transpose();
    const Eigen::VectorXd var = gp.variances(moved);
    double sum = 0;
    for (Eigen::Index i = 0; i < points.rows(); ++i)
        sum += (query.row(i).transpose() - gp.mean(moved.row(i).transpose())).squaredNorm() / var[i];
    return std::sqrt(sum / double(query.size()));
}
}  // namespace

Eigen::Vector2d PlanarAlignmentResult::apply(const Eigen::Vector2d& p) const {
    return pivot + rotation(delta[2]) * (p - pivot) + delta.head<2>();
}

PlanarAlignmentResult alignInPlane(const GaussianProcess2D& gp, const Eigen::MatrixX2d& points,
                                   const Eigen::MatrixXd& query, const PlanarAlignmentParams& params) {
    PlanarAlignmentResult result;
    if (points.rows() < 3 || points.rows() != query.rows()) return result;
    result.pivot = points.colwise().mean().transpose();
    // Each reading weighed by the predictive sigma where it starts (fixed, so the steps are
    // plain Gauss-Newton on the mean); the variance enters the final score.
    const Eigen::VectorXd sigma = gp.variances(points).cwiseSqrt();
    const Eigen::Vector3d priorInfo(1 / (params.priorSigmaXY * params.priorSigmaXY),
                                    1 / (params.priorSigmaXY * params.priorSigmaXY),
                                    1 / (params.priorSigmaYaw * params.priorSigmaYaw));
    result.normalizedRmsStart = normalizedRms(gp, points, query, result);
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    Eigen::Matrix3d H;
    Eigen::Vector3d g;
    double cost = evaluate(gp, points, query, sigma, result.pivot, x, priorInfo, &H, &g);
    double lambda = 1e-3;
    for (int it = 0; it < params.iterations; ++it) {
        Eigen::Matrix3d A = H;
        A.diagonal() *= 1 + lambda;
        const Eigen::Vector3d step = A.ldlt().solve(-g);
        const Eigen::Vector3d next = x + step;
        Eigen::Matrix3d Hn;
        Eigen::Vector3d gn;
        const double c = evaluate(gp, points, query, sigma, result.pivot, next, priorInfo, &Hn, &gn);
        if (c < cost) {
            x = next;
            cost = c;
            H = Hn;
            g = gn;
            lambda = std::max(1e-6, lambda / 4);
            if (step.head<2>().norm() < 1e-3 && std::abs(step[2]) < 1e-3) break;  // [m], [rad]
        } else {
            lambda *= 8;
            if (lambda > 1e6) break;
        }
    }
    result.delta = x;
    result.covariance = H.inverse();
    result.normalizedRms = normalizedRms(gp, points, query, result);
    // A poor fit says the sigmas are optimistic: scale by the residual's excess.
    result.covariance *= std::max(1.0, result.normalizedRms * result.normalizedRms);
    for (int k = 0; k < 2; ++k)
        result.covariance(k, k) += params.minSigma * params.minSigma;
    result.valid = x.head<2>().norm() <= params.maxShift && std::isfinite(result.normalizedRms);
    return result;
}

}  // namespace lodestone::magnetic
