#include <lodestone/vision/depth/PointToPlaneIcp.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace lodestone::vision {

const char* toString(DepthAlignFailure f) {
    switch (f) {
        case DepthAlignFailure::None:
            return "none";
        case DepthAlignFailure::FewPoints:
            return "too few depth points";
        case DepthAlignFailure::FewCorrespondences:
            return "too few depth correspondences";
        case DepthAlignFailure::Unobservable:
            return "depth does not pin the motion";
    }
    return "?";
}

namespace {
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
    Eigen::Matrix3d S;
    S << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
    return S;
}

/** One pass over the correspondences at a motion: the normal equations (twists about the
 * reference's origin) and the geometry they saw. */
struct Pass {
    Matrix6d H{Matrix6d::Zero()};
    Vector6d g{Vector6d::Zero()};
    double chi2{0}, sumSquares{0};
    std::size_t n{0};
    std::vector<Eigen::Vector3d> points, normals;  ///< matched points (reference frame), model normals
    double normalVariance{0};                      ///< mean over the matches [rad^2]
};

/** exp(dx) T for a left perturbation dx = (w, v): p' = R(w) (T p) + v. */
Eigen::Isometry3d leftUpdate(const Vector6d& dx, const Eigen::Isometry3d& T) {
    const Eigen::Vector3d w = dx.head<3>();
    Eigen::Isometry3d D = Eigen::Isometry3d::Identity();
    const double angle = w.norm();
    if (angle > 0) D.linear() = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
    D.translation() = dx.tail<3>();
    return D * T;
}

/** The directions the matched geometry pins (Gelfand et al., "Geometrically stable sampling for
 * the ICP algorithm", 2003): twists about the points' centroid c with rotations scaled by the
 * points' spread L, xi_s = A xi = (L w, v + w x c), in which every point-to-plane row is
 * ((p - c) / L x n, n). The eigenvalues of the mean of their outer products are the share of
 * the surface that faces each direction; a plane's noisy normals alone give about the normals'
 * variance in its own directions. */
struct Geometry {
    Matrix6d A, Ainv;
    Eigen::Matrix<double, 6, Eigen::Dynamic> observed, unobserved;  ///< bases, xi_s coordinates
    double spread{1};
};

Geometry geometryOf(const Pass& pass, double noiseChi2, double minStructure) {
    Geometry geo;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const auto& p : pass.points) c += p;
    c /= static_cast<double>(pass.points.size());
    double spread2 = 0;
    for (const auto& p : pass.points) spread2 += (p - c).squaredNorm();
    geo.spread = std::max(1e-3, std::sqrt(spread2 / static_cast<double>(pass.points.size())));
    const double L = geo.spread;
    Matrix6d M = Matrix6d::Zero();
    for (std::size_t i = 0; i < pass.points.size(); ++i) {
        Vector6d row;
        row.head<3>() = ((pass.points[i] - c) / L).cross(pass.normals[i]);
        row.tail<3>() = pass.normals[i];
        M.noalias() += row * row.transpose();
    }
    M /= static_cast<double>(pass.points.size());
    const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(M);
    const double floor = std::max(minStructure, noiseChi2 * pass.normalVariance);
    int k = 0;
    for (int i = 0; i < 6; ++i) k += eig.eigenvalues()(i) >= floor ? 1 : 0;
    geo.observed.resize(6, k);
    geo.unobserved.resize(6, 6 - k);
    int o = 0, u = 0;
    for (int i = 0; i < 6; ++i) {
        if (eig.eigenvalues()(i) >= floor) {
            geo.observed.col(o++) = eig.eigenvectors().col(i);
        } else {
            geo.unobserved.col(u++) = eig.eigenvectors().col(i);
        }
    }
    geo.A.setZero();
    geo.A.topLeftCorner<3, 3>() = L * Eigen::Matrix3d::Identity();
    geo.A.bottomLeftCorner<3, 3>() = -skew(c);
    geo.A.bottomRightCorner<3, 3>().setIdentity();
    geo.Ainv.setZero();
    geo.Ainv.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() / L;
    geo.Ainv.bottomLeftCorner<3, 3>() = skew(c) / L;
    geo.Ainv.bottomRightCorner<3, 3>().setIdentity();
    return geo;
}

/** A step `dx` (the camera's twist) that moves only along the pinned directions fits the depth
 * as well with any step along the unpinned ones added: of those, the one that moves the camera
 * least (rotations counted in metres at the spread, as the pinned basis does). The pinned
 * directions are about the matched surface's centroid: a wall's tilt pinned about its centre a
 * metre ahead, with the centre's in-plane motion left as it was, turns the camera's pitch into
 * a rise of the camera (a metre times the pitch, every frame a hand shakes) - the surface
 * cannot tell, the carrier's motion model can, and it is about the camera. */
Vector6d keepCameraWherePinnedNothing(const Vector6d& dx, const Geometry& geo) {
    const auto& N = geo.unobserved;
    if (N.cols() == 0) return dx;
    // dx + Ainv N z, least in the camera's own (w L, v) norm.
    Matrix6d W = Matrix6d::Identity();
    W.topLeftCorner<3, 3>() *= geo.spread * geo.spread;
    const Eigen::MatrixXd D = geo.Ainv * N;
    const Eigen::MatrixXd DtW = D.transpose() * W;
    const Eigen::VectorXd z = -(DtW * D).ldlt().solve(DtW * dx);
    return dx + D * z;
}

/** log(T T0^-1) in leftUpdate's coordinates: T = exp(d) T0. */
Vector6d leftDifference(const Eigen::Isometry3d& T, const Eigen::Isometry3d& T0) {
    const Eigen::Isometry3d D = T * T0.inverse();
    const Eigen::AngleAxisd aa(D.rotation());
    Vector6d d;
    d << aa.angle() * aa.axis(), D.translation();
    return d;
}

/** One pass of correspondences at T: each current point's nearest model point within `gate`
 * whose normal agrees, weighed by both points' depth noise and Huber's loss (`huber` sigmas);
 * the normal equations of the point-to-plane residuals. */
Pass correspondencesAt(const DepthModel& model, const DepthCloud& current,
                       const Eigen::Isometry3d& T, double gate, float cosNormal, double huber,
                       std::vector<std::int64_t>& lastNearest) {
    Pass e;
    const Eigen::Matrix3f R = T.linear().cast<float>();
    const Eigen::Vector3f t = T.translation().cast<float>();
    const auto gate2 = static_cast<float>(gate * gate);
    DepthModel::Nearest nn;
    e.points.reserve(static_cast<std::size_t>(current.points.cols()));
    e.normals.reserve(static_cast<std::size_t>(current.points.cols()));
    for (Eigen::Index i = 0; i < current.points.cols(); ++i) {
        const Eigen::Vector3f p = R * current.points.col(i) + t;
        auto& near = lastNearest[static_cast<std::size_t>(i)];
        if (!model.nearest(p, gate2, nn, near)) {
            near = -1;
            continue;
        }
        near = nn.index;
        if ((R * current.normals.col(i)).dot(nn.normal) < cosNormal) continue;
        const double r = nn.normal.dot(p - nn.point);
        const double sigma2 =
            double(current.sigma(i)) * current.sigma(i) + double(nn.sigma) * nn.sigma;
        const double e1 = std::abs(r) / std::sqrt(sigma2);
        const double w = (e1 <= huber ? 1.0 : huber / e1) / sigma2;
        Vector6d J;
        J.head<3>() = p.cast<double>().cross(nn.normal.cast<double>());
        J.tail<3>() = nn.normal.cast<double>();
        e.H.noalias() += w * J * J.transpose();
        e.g.noalias() += w * r * J;
        e.chi2 += w * r * r;
        e.sumSquares += r * r;
        e.points.push_back(p.cast<double>());
        e.normals.push_back(nn.normal.cast<double>());
        e.normalVariance += nn.normalVariance;
        ++e.n;
    }
    if (e.n > 0) e.normalVariance /= static_cast<double>(e.n);
    return e;
}

/** Where the depth's and a measured motion disagree beyond chance in the directions the depth
 * pins (chi-square over those directions, 99 %), one of the covariances is too tight - which,
 * neither says - so the joint one is scaled to cover the disagreement (the adjustment's
 * a-posteriori variance factor). `varianceFactor`: the last pass's, as its Hessian was scaled. */
void scaleByDisagreement(const Pass& e, const Geometry& geo, double varianceFactor,
                         const Eigen::Isometry3d& T, const MotionPrior& measured,
                         const Matrix6d& measuredInformation, Matrix6d& jointInverse,
                         DepthAlignment& a) {
    const auto& U = geo.observed;
    const int k = static_cast<int>(U.cols());
    if (k > 0) {
        const double vf = varianceFactor;
        const Eigen::MatrixXd Hu =
            U.transpose() * (geo.Ainv.transpose() * e.H * geo.Ainv / vf) * U;
        const Eigen::VectorXd offset =
            Hu.ldlt().solve(U.transpose() * (geo.Ainv.transpose() * e.g / vf));
        const Vector6d ds = geo.A * leftDifference(T, measured.T_ref_cur);
        const Matrix6d Ls = geo.Ainv.transpose() * measuredInformation * geo.Ainv;
        a.disagreement = offset.dot(Hu * offset) + ds.dot(Ls * ds);
        constexpr double kChi2Quantile99[7] = {0, 6.63, 9.21, 11.34, 13.28, 15.09, 16.81};
        a.disagreed = a.disagreement > kChi2Quantile99[k];
        if (a.disagreed) jointInverse *= a.disagreement / k;
    }
}
}  // namespace

DepthAlignment PointToPlaneIcp::align(const DepthModel& model, const DepthCloud& current,
                                      const Eigen::Isometry3d& initial,
                                      const MotionPrior* measured) const {
    DepthAlignment a;
    a.points = current.size();
    a.T_ref_cur = initial;
    if (current.size() < params_.minCorrespondences || model.size() < params_.minCorrespondences) {
        a.failure = DepthAlignFailure::FewPoints;
        return a;
    }
    const float cosNormal = static_cast<float>(std::cos(params_.maxNormalAngle));
    // Each point's nearest model point in the last pass: it bounds the next pass's search (the
    // motion between passes is small).
    std::vector<std::int64_t> lastNearest(static_cast<std::size_t>(current.points.cols()), -1);

    Eigen::Isometry3d T = initial;
    Pass e;
    Geometry geo;
    Eigen::MatrixXd reducedInverse;  // (U_o^T H_s U_o)^-1 of the last pass
    Matrix6d jointInverse;           // with a measured motion: (H_o + Lambda_s)^-1
    double varianceFactor = 1;       // the last pass's residuals' chi-square per dof (>= 1)
    Matrix6d measuredInformation = Matrix6d::Zero();
    if (measured) {
        measuredInformation = measured->covariance.ldlt().solve(Matrix6d::Identity());
        measuredInformation = 0.5 * (measuredInformation + measuredInformation.transpose());
    }
    for (int it = 0; it < params_.iterations; ++it) {
        const double gate = std::max(params_.minDistance, params_.maxDistance * std::pow(0.6, it));
        e = correspondencesAt(model, current, T, gate, cosNormal, params_.huber, lastNearest);
        a.iterations = it + 1;
        if (e.n < params_.minCorrespondences) break;
        geo = geometryOf(e, params_.normalNoiseChi2, params_.minStructure);
        // Gauss-Newton in the pinned directions only; along the others T keeps the initial motion.
        varianceFactor = std::max(1.0, e.chi2 / static_cast<double>(e.n - 6));
        const Matrix6d Hs = geo.Ainv.transpose() * e.H * geo.Ainv / varianceFactor;
        const Vector6d gs = geo.Ainv.transpose() * e.g / varianceFactor;
        const auto& U = geo.observed;
        Vector6d dx;
        if (measured) {
            // The depth's information in the directions it pins, the measurement's in all.
            const Matrix6d P = U * U.transpose();
            const Matrix6d Ls = geo.Ainv.transpose() * measuredInformation * geo.Ainv;
            const Matrix6d Hj = P * Hs * P + Ls;
            jointInverse = Hj.ldlt().solve(Matrix6d::Identity());
            const Vector6d ds = geo.A * leftDifference(T, measured->T_ref_cur);
            dx = geo.Ainv * (-jointInverse * (P * gs + Ls * ds));
        } else {
            if (U.cols() == 0) break;
            reducedInverse = (U.transpose() * Hs * U).inverse();
            dx = geo.Ainv * (-U * (reducedInverse * (U.transpose() * gs)));
            dx = keepCameraWherePinnedNothing(dx, geo);
        }
        T = leftUpdate(dx, T);
        if (gate <= params_.minDistance && dx.head<3>().norm() < 1e-6 && dx.tail<3>().norm() < 1e-6) {
            break;
        }
    }
    a.correspondences = e.n;
    a.rmse = e.n > 0 ? std::sqrt(e.sumSquares / static_cast<double>(e.n)) : 0;
    if (e.n < params_.minCorrespondences ||
        static_cast<double>(e.n) < params_.minOverlap * static_cast<double>(current.size())) {
        a.failure = DepthAlignFailure::FewCorrespondences;
        return a;
    }
    a.observed = static_cast<int>(geo.observed.cols());
    a.T_ref_cur = T;
    if (measured) {
        // The two measurements overlap in the directions the depth pins.
        scaleByDisagreement(e, geo, varianceFactor, T, *measured, measuredInformation, jointInverse, a);
        a.covariance = geo.Ainv * jointInverse * geo.Ainv.transpose();
        a.success = true;
        return a;
    }
    Matrix6d Cs = geo.unobserved * geo.unobserved.transpose() *
                  (params_.unobservedSigma * params_.unobservedSigma);
    if (a.observed > 0) Cs += geo.observed * reducedInverse * geo.observed.transpose();
    a.covariance = geo.Ainv * Cs * geo.Ainv.transpose();
    if (a.observed < params_.minObserved) {
        a.failure = DepthAlignFailure::Unobservable;
        return a;
    }
    a.success = true;
    return a;
}

}  // namespace lodestone::vision
