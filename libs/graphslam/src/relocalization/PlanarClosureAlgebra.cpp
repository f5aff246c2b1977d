#include <lodestone/graphslam/relocalization/PlanarClosureAlgebra.h>

#include <mrpt/math/wrap2pi.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>

namespace lodestone::graphslam::relocalization {

namespace {

Pose2 inverse(const Pose2& p) {
    Pose2 q = p;
    q.inverse();
    return q;
}

constexpr int kPlanarFromMrpt[3] = {0, 1, 3};

/** Central-difference Jacobian of f (R^3 -> R^3) at v, the output's yaw difference wrapped. */
template <typename F>
Matrix3 jacobian(const F& f, const Vector3& v) {
    constexpr double h = 1e-6;
    Matrix3 J;
    for (int k = 0; k < 3; ++k) {
        Vector3 lo = v, hi = v;
        lo[k] -= h;
        hi[k] += h;
        Vector3 d = f(hi) - f(lo);
        d[2] = mrpt::math::wrapToPi(d[2]);
        J.col(k) = d / (2 * h);
    }
    return J;
}

Pose2 moved(const Pose2& T, const Pose2& u) { return T + u; }

Vector3 residualAfter(const Hypothesis& h, const Pose2& T) {
    const Pose2 u = moved(T, h.u);
    return h.uIsTo ? closureResidual(h.a, u, h.z) : closureResidual(u, h.a, h.z);
}

/** Where a closure from anchored pose `a` puts its moving end, in the anchored frame. */
Pose2 mapPoseOfU(const Pose2& a, const Pose2& z, bool uIsTo) {
    return uIsTo ? a + z : a + inverse(z);
}

}  // namespace

Pose2 planar(const mrpt::poses::CPose3D& p) { return Pose2(p.x(), p.y(), p.yaw()); }

Vector3 vectorOf(const Pose2& p) { return Vector3(p.x(), p.y(), mrpt::math::wrapToPi(p.phi())); }

Pose2 poseOf(const Vector3& v) { return Pose2(v[0], v[1], v[2]); }

Matrix3 planarInformation(const Constraint& c) {
    Matrix3 I;
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) I(r, k) = c.cov_inv(kPlanarFromMrpt[r], kPlanarFromMrpt[k]);
    return I;
}

Matrix3 planarCovariance(const Constraint& c) {
    return planarInformation(c).ldlt().solve(Matrix3::Identity());
}

Vector3 closureResidual(const Pose2& from, const Pose2& to, const Pose2& z) {
    return vectorOf(inverse(z) + (inverse(from) + to));
}

Pose2 impliedTransform(const Pose2& a, const Pose2& u, const Pose2& z, bool uIsTo) {
    return mapPoseOfU(a, z, uIsTo) + inverse(u);
}

double pairwiseChi2(const Hypothesis& i, const Hypothesis& j, const Matrix3& odometryCov,
                    const Matrix3& mapCov) {
    const Vector3 zi = vectorOf(i.z), zj = vectorOf(j.z);
    const Vector3 d = vectorOf(inverse(i.u) + j.u);
    const Vector3 m = vectorOf(inverse(i.a) + j.a);
    // e = d^-1 (+) (P_i^-1 (+) P_j): the moved group's own relative pose against the one the
    // two closures imply, P_i = a_i (+) z_i and P_j = a_i (+) m (+) z_j.
    const auto error = [&](const Vector3& zi_, const Vector3& zj_, const Vector3& d_,
                           const Vector3& m_) {
        const Pose2 Pi = mapPoseOfU(i.a, poseOf(zi_), i.uIsTo);
        const Pose2 Pj = mapPoseOfU(i.a + poseOf(m_), poseOf(zj_), j.uIsTo);
        return vectorOf(inverse(poseOf(d_)) + (inverse(Pi) + Pj));
    };
    const Vector3 e = error(zi, zj, d, m);
    const Matrix3 Ji = jacobian([&](const Vector3& v) { return error(v, zj, d, m); }, zi);
    const Matrix3 Jj = jacobian([&](const Vector3& v) { return error(zi, v, d, m); }, zj);
    const Matrix3 Jd = jacobian([&](const Vector3& v) { return error(zi, zj, v, m); }, d);
    const Matrix3 Jm = jacobian([&](const Vector3& v) { return error(zi, zj, d, v); }, m);
    const Matrix3 S = Ji * i.cov * Ji.transpose() + Jj * j.cov * Jj.transpose() +
                      Jd * odometryCov * Jd.transpose() + Jm * mapCov * Jm.transpose();
    return e.dot(S.ldlt().solve(e));
}

double chi2After(const Hypothesis& h, const Pose2& T) {
    const Vector3 r = residualAfter(h, T);
    return r.dot(h.cov.ldlt().solve(r));
}

Matrix3 movedPoseCovariance(const Pose2& T, const Matrix3& covT, const Pose2& u) {
    const Matrix3 J =
        jacobian([&](const Vector3& v) { return vectorOf(moved(poseOf(v), u)); }, vectorOf(T));
    return J * covT * J.transpose();
}

Pose2 fitTransform(const std::vector<Hypothesis>& hs, const Pose2& start, Matrix3* covariance) {
    Vector3 t = vectorOf(start);
    Matrix3 H = Matrix3::Identity();
    for (int iteration = 0; iteration < 20; ++iteration) {
        H = Matrix3::Zero();
        Vector3 g = Vector3::Zero();
        for (const auto& h : hs) {
            const Matrix3 W = h.cov.ldlt().solve(Matrix3::Identity());
            const auto r = [&](const Vector3& v) { return residualAfter(h, poseOf(v)); };
            const Matrix3 J = jacobian(r, t);
            const Vector3 e = r(t);
            H += J.transpose() * W * J;
            g += J.transpose() * W * e;
        }
        const Vector3 step = -H.ldlt().solve(g);
        if (!step.allFinite()) break;
        t += step;
        t[2] = mrpt::math::wrapToPi(t[2]);
        if (step.head<2>().norm() < 1e-7 && std::abs(step[2]) < 1e-9) break;
    }
    if (covariance) *covariance = H.ldlt().solve(Matrix3::Identity());
    return poseOf(t);
}

}  // namespace lodestone::graphslam::relocalization
