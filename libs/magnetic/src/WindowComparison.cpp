#include <lodestone/magnetic/WindowComparison.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <stdexcept>

namespace lodestone::magnetic {

WindowFit compareWindows(const std::vector<TrackSample>& querySamples, std::size_t query,
                         const std::vector<TrackSample>& targetSamples, std::size_t target,
                         std::size_t n, WindowDirection direction, const PassNoise& noise,
                         double turnPrior, double turnPriorVariance) {
    // Horizontal parts h, turned by theta: |h_q - R(theta) h_t|^2 summed is
    // K - 2 (C cos theta + S sin theta) = K - 2 M cos(theta - theta*), with C the dot and S the
    // cross products summed; theta = -(psi_q - psi_t) since readings are in the robot frame.
    // The offset and trend see the differences only through their plain and x-weighted sums
    // (x: a reading's place in the window, centred), linear in each side's sums.
    double vertical = 0, K = 0, C = 0, S = 0, xx = 0;
    Eigen::Vector3d sq = Eigen::Vector3d::Zero(), st = sq, xq = sq, xt = sq;
    for (std::size_t k = 0; k < n; ++k) {
        const auto& q = querySamples[query + k].value;
        const auto& t =
            targetSamples[direction == WindowDirection::Forward ? target + k : target + n - 1 - k]
                .value;
        const double dz = double(q[2]) - double(t[2]);
        vertical += dz * dz;
        K += double(q[0]) * q[0] + double(q[1]) * q[1] + double(t[0]) * t[0] + double(t[1]) * t[1];
        C += double(t[0]) * q[0] + double(t[1]) * q[1];
        S += double(t[0]) * q[1] - double(t[1]) * q[0];
        const double x = (double(k) - 0.5 * double(n - 1)) * noise.step;
        const Eigen::Vector3d qv = q.head<3>().cast<double>(), tv = t.head<3>().cast<double>();
        sq += qv;
        st += tv;
        xq += x * qv;
        xt += x * tv;
        xx += x * x;
    }
    const double s2 = noise.sigma * noise.sigma;
    const double M = std::hypot(C, S);
    const double thetaStar = std::atan2(S, C);
    // Near theta* the field term is (K - 2M)/s2 + (M/s2)(theta - theta*)^2: information M/s2,
    // combined with the prior's 1/variance (the prior wrapped next to theta*).
    const double fieldInfo = M / s2;
    const double priorInfo =
        std::isfinite(turnPriorVariance) && turnPriorVariance > 0 ? 1.0 / turnPriorVariance : 0.0;
    const double theta0 = thetaStar + std::remainder(-turnPrior - thetaStar, 2 * M_PI);
    WindowFit fit;
    const double info = fieldInfo + priorInfo;
    const double theta = info > 0 ? (fieldInfo * thetaStar + priorInfo * theta0) / info : thetaStar;
    double white = (vertical + K - 2 * M * std::cos(theta - thetaStar)) / s2;
    // Woodbury: d'(s2 I + b2 11' + t2 xx')^-1 d = (|d|^2 - (1'd)^2 / (n + s2/b2)
    // - (x'd)^2 / (x'x + s2/t2)) / s2, per component (1 and x are orthogonal).
    const double c = std::cos(theta), s = std::sin(theta);
    const auto turned = [&](const Eigen::Vector3d& v) {
        return Eigen::Vector3d(c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z());
    };
    if (noise.biasSigma > 0) {
        const Eigen::Vector3d sd = sq - turned(st);
        white -= sd.squaredNorm() / (double(n) + s2 / (noise.biasSigma * noise.biasSigma)) / s2;
    }
    if (noise.trendSigma > 0) {
        const Eigen::Vector3d xd = xq - turned(xt);
        white -= xd.squaredNorm() / (xx + s2 / (noise.trendSigma * noise.trendSigma)) / s2;
    }
    fit.turnPriorChi2 = priorInfo * (theta - theta0) * (theta - theta0);
    fit.chi2 = white + fit.turnPriorChi2;
    fit.turn = std::remainder(-theta, 2 * M_PI);
    fit.turnVariance = info > 0 ? 1.0 / info : INFINITY;
    return fit;
}

Eigen::MatrixX3d windowResiduals(const std::vector<TrackSample>& querySamples, std::size_t query,
                                 const std::vector<TrackSample>& targetSamples, std::size_t target,
                                 std::size_t n, WindowDirection direction, const WindowFit& fit) {
    // The target's horizontal parts turned into the query's frame: R(-turn).
    const double c = std::cos(fit.turn), s = std::sin(fit.turn);
    Eigen::MatrixX3d d(static_cast<Eigen::Index>(n), 3);
    for (std::size_t k = 0; k < n; ++k) {
        const auto& q = querySamples[query + k].value;
        const auto& t =
            targetSamples[direction == WindowDirection::Forward ? target + k : target + n - 1 - k]
                .value;
        const auto r = static_cast<Eigen::Index>(k);
        d(r, 0) = double(q[0]) - (c * t[0] + s * t[1]);
        d(r, 1) = double(q[1]) - (-s * t[0] + c * t[1]);
        d(r, 2) = double(q[2]) - double(t[2]);
    }
    return d;
}

Eigen::MatrixXd passNoiseCovariance(std::size_t n, const PassNoise& noise) {
    const auto m = static_cast<Eigen::Index>(n);
    Eigen::VectorXd x(m);
    for (Eigen::Index i = 0; i < m; ++i) x[i] = (double(i) - 0.5 * double(n - 1)) * noise.step;
    Eigen::MatrixXd C = noise.sigma * noise.sigma * Eigen::MatrixXd::Identity(m, m);
    C.array() += noise.biasSigma * noise.biasSigma;
    C += noise.trendSigma * noise.trendSigma * x * x.transpose();
    return C;
}

WindowNullModel::WindowNullModel(std::size_t n, const PassNoise& noise, double sigmaF,
                                 double lengthScale) {
    const auto m = static_cast<Eigen::Index>(n);
    const Eigen::MatrixXd same = passNoiseCovariance(n, noise);
    Eigen::MatrixXd unrelated = same;
    for (Eigen::Index i = 0; i < m; ++i) {
        for (Eigen::Index j = 0; j < m; ++j) {
            const double r = double(i - j) * noise.step / lengthScale;
            unrelated(i, j) += 2 * sigmaF * sigmaF * std::exp(-0.5 * r * r);
        }
    }
    const Eigen::LLT<Eigen::MatrixXd> a(same), b(unrelated);
    same_inverse_ = a.solve(Eigen::MatrixXd::Identity(m, m));
    null_inverse_ = b.solve(Eigen::MatrixXd::Identity(m, m));
    const auto logDet = [](const Eigen::LLT<Eigen::MatrixXd>& l) {
        return 2 * l.matrixLLT().diagonal().array().log().sum();
    };
    // Per component: -1/2 log det(2 pi C1) + 1/2 log det(2 pi C0); three components.
    log_normalizers_ = 3 * 0.5 * (logDet(b) - logDet(a));
}

double WindowNullModel::logLikelihoodRatio(const Eigen::MatrixX3d& d) const {
    double same = 0, unrelated = 0;
    for (int c = 0; c < 3; ++c) {
        same += d.col(c).dot(same_inverse_ * d.col(c));
        unrelated += d.col(c).dot(null_inverse_ * d.col(c));
    }
    return -0.5 * same + 0.5 * unrelated + log_normalizers_;
}

double windowExcitation(const std::vector<TrackSample>& samples, std::size_t first, std::size_t n,
                        double sigma) {
    if (n < 2) return 0;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < n; ++k) mean += samples[first + k].value.head<3>().cast<double>();
    mean /= double(n);
    double sum = 0;
    for (std::size_t k = 0; k < n; ++k)
        sum += (samples[first + k].value.head<3>().cast<double>() - mean).squaredNorm();
    return sum / (sigma * sigma);
}

double chiSquareQuantile(double dof, double p) {
    if (!(dof > 0) || !(p > 0 && p < 1))
        throw std::invalid_argument("chiSquareQuantile: bad input");
    // The standard normal quantile, by bisection on the normal CDF (exact to 1e-12).
    double lo = -40, hi = 40;
    for (int i = 0; i < 200 && hi - lo > 1e-12; ++i) {
        const double mid = 0.5 * (lo + hi);
        (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
    }
    const double z = 0.5 * (lo + hi);
    const double a = 2.0 / (9.0 * dof);
    const double c = 1 - a + z * std::sqrt(a);
    return dof * c * c * c;
}

}  // namespace lodestone::magnetic
