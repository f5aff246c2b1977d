#include <lodestone/config/IniSection.h>
#include <lodestone/vision/RigidRansac.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <random>

namespace lodestone::vision {

void RigidRansac::Params::loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                             const std::string& section) {
    config::IniSection s(source, section, config::sourceName(source));
    read(s);
}

void RigidRansac::Params::read(config::IniSection& s) {
    iterations = s.getInt("ransac_iterations", iterations);
    threshold = s.getDouble("ransac_threshold", threshold);
    depthScale = s.getDouble("ransac_depth_scale", depthScale);
    minInliers = s.getInt("min_inliers", minInliers);
    minInlierRatio = s.getDouble("min_inlier_ratio", minInlierRatio);
    pointNoise = s.getDouble("point_noise", pointNoise);
    depthNoise = s.getDouble("point_depth_noise", depthNoise);
    if (pointNoise <= 0) s.fail("point_noise", "must be > 0");
    if (iterations < 1) s.fail("ransac_iterations", "must be >= 1");
    if (threshold <= 0) s.fail("ransac_threshold", "must be > 0");
    if (minInliers < 3) s.fail("min_inliers", "must be >= 3");
}

void RigidRansac::Params::dumpToTextStream(std::ostream& out) const {
    out << "ransac_iterations  = " << iterations << "\n"
        << "ransac_threshold   = " << threshold << "  [m]\n"
        << "ransac_depth_scale = " << depthScale << "  [1/m]\n"
        << "min_inliers        = " << minInliers << "\n"
        << "min_inlier_ratio   = " << minInlierRatio << "\n"
        << "point_noise        = " << pointNoise << "  [m]\n"
        << "point_depth_noise  = " << depthNoise << "  [1/m]\n";
}

Eigen::Isometry3d alignRigid(const Eigen::Matrix3Xd& src, const Eigen::Matrix3Xd& dst) {
    Eigen::Isometry3d T;
    T.matrix() = Eigen::umeyama(src, dst, false);
    return T;
}

Eigen::Isometry3d alignRigidWeighted(const Eigen::Matrix3Xd& src, const Eigen::Matrix3Xd& dst,
                                     const Eigen::VectorXd& weights) {
    // Paper 001's SVD solution with a weight per pair: weighted centroids, W = sum w q' q^T.
    const double total = weights.sum();
    const Eigen::Vector3d cs = (src * weights) / total, cd = (dst * weights) / total;
    const Eigen::Matrix3Xd qs = src.colwise() - cs, qd = dst.colwise() - cd;
    const Eigen::Matrix3d W = qs * weights.asDiagonal() * qd.transpose();
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(W, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
    D(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1 : 1;  // no mirror
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = svd.matrixV() * D * svd.matrixU().transpose();
    T.translation() = cd - T.linear() * cs;
    return T;
}

RigidRansac::RigidRansac() : RigidRansac(Params()) {}

RigidRansac::RigidRansac(const Params& params) : params_(params) {}

std::vector<int> RigidRansac::inliersOf(const Eigen::Isometry3d& T, const Eigen::Matrix3Xd& src,
                                        const Eigen::Matrix3Xd& dst) const {
    std::vector<int> in;
    for (Eigen::Index i = 0; i < src.cols(); ++i) {
        const double z = dst(2, i);
        const double gate = params_.threshold + params_.depthScale * z * z;
        if ((T * src.col(i) - dst.col(i)).squaredNorm() < gate * gate)
            in.push_back(static_cast<int>(i));
    }
    return in;
}

RigidEstimate RigidRansac::estimate(const Eigen::Matrix3Xd& src, const Eigen::Matrix3Xd& dst,
                                    std::uint64_t seed) const {
    RigidEstimate best;
    const Eigen::Index n = src.cols();
    if (n < 3 || dst.cols() != n) return best;
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<Eigen::Index> pick(0, n - 1);
    Eigen::Matrix3Xd s(3, 3), d(3, 3);
    int needed = params_.iterations;  // lowered by the adaptive stop, when on
    for (int it = 0; it < needed; ++it) {
        Eigen::Index idx[3] = {pick(rng), pick(rng), pick(rng)};
        if (idx[0] == idx[1] || idx[1] == idx[2] || idx[0] == idx[2]) continue;
        for (int k = 0; k < 3; ++k) {
            s.col(k) = src.col(idx[k]);
            d.col(k) = dst.col(idx[k]);
        }
        // A degenerate (nearly collinear) sample gives no rotation.
        if ((s.col(1) - s.col(0)).cross(s.col(2) - s.col(0)).norm() < 1e-4) continue;
        const Eigen::Isometry3d T = alignRigid(s, d);
        auto in = inliersOf(T, src, dst);
        if (in.size() > best.inliers.size()) {
            best.inliers = std::move(in);
            best.transform = T;
            if (params_.confidence > 0) {
                // Enough samples that one all-inlier sample was drawn with this confidence,
                // given the best inlier ratio so far.
                const double w = static_cast<double>(best.inliers.size()) / static_cast<double>(n);
                const double allInlier = w * w * w;
                if (allInlier >= 1.0) {
                    needed = std::min(needed, it + 1);
                } else if (allInlier > 0) {
                    const double k = std::log(1 - params_.confidence) / std::log(1 - allInlier);
                    needed = std::min(needed, static_cast<int>(std::ceil(k)) + 1);
                }
            }
        }
    }
    if (best.inliers.size() < 3) return best;
    // Each pair weighted by its expected noise: depth noise grows with z^2 in both points.
    const auto weightOf = [&](int i) {
        const auto sigma = [&](double z) {
            return params_.pointNoise + params_.depthNoise * z * z;
        };
        const double s1 = sigma(src(2, i)), s2 = sigma(dst(2, i));
        return 1.0 / (s1 * s1 + s2 * s2);
    };
    // Refit on every inlier, then take the inliers of the refit (twice is enough in practice).
    for (int pass = 0; pass < 2; ++pass) {
        Eigen::Matrix3Xd si(3, best.inliers.size()), di(3, best.inliers.size());
        Eigen::VectorXd wi(static_cast<Eigen::Index>(best.inliers.size()));
        for (std::size_t k = 0; k < best.inliers.size(); ++k) {
            si.col(static_cast<Eigen::Index>(k)) = src.col(best.inliers[k]);
            di.col(static_cast<Eigen::Index>(k)) = dst.col(best.inliers[k]);
            wi[static_cast<Eigen::Index>(k)] = weightOf(best.inliers[k]);
        }
        best.transform = alignRigidWeighted(si, di, wi);
        auto in = inliersOf(best.transform, src, dst);
        if (in.size() < 3) break;
        best.inliers = std::move(in);
    }
    // Residuals and the covariance of a left perturbation: r_i = exp(xi) T src_i - dst_i,
    // dr/dxi = [ -[T src_i]x  I ].
    const auto m = static_cast<Eigen::Index>(best.inliers.size());
    Eigen::Matrix<double, 6, 6> JtJ = Eigen::Matrix<double, 6, 6>::Zero();
    double ssr = 0, weighted = 0;
    for (const int i : best.inliers) {
        const Eigen::Vector3d p = best.transform * src.col(i);
        const double w = weightOf(i);
        ssr += (p - dst.col(i)).squaredNorm();
        weighted += w * (p - dst.col(i)).squaredNorm();
        Eigen::Matrix<double, 3, 6> J;
        J << 0, p.z(), -p.y(), 1, 0, 0,  //
            -p.z(), 0, p.x(), 0, 1, 0,   //
            p.y(), -p.x(), 0, 0, 0, 1;
        JtJ += w * J.transpose() * J;
    }
    best.rmse = std::sqrt(ssr / static_cast<double>(m));
    // The weights' scale, re-estimated from the residuals (1 when the noise model is right).
    const double sigma2 = m > 2 ? weighted / static_cast<double>(3 * m - 6) : weighted;
    const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> lu(JtJ);
    best.covariance = lu.isInvertible() ? Eigen::Matrix<double, 6, 6>(sigma2 * lu.inverse())
                                        : Eigen::Matrix<double, 6, 6>::Identity();
    best.success = lu.isInvertible() && m >= params_.minInliers &&
                   static_cast<double>(m) >= params_.minInlierRatio * static_cast<double>(n);
    return best;
}

}  // namespace lodestone::vision
