#include <lodestone/graphslam/relocalization/ClosureAlgebra.h>

#include <Eigen/Cholesky>
#include <cmath>

namespace lodestone::graphslam::relocalization {

namespace {

/** Central-difference Jacobian of f (a pose -> S's vector) at `at`, in S's perturbation chart;
 * differences of the output wrapped (angles). */
template <class S, typename F>
typename S::Matrix jacobian(const F& f, const typename S::Pose& at) {
    constexpr double h = 1e-6;
    typename S::Matrix J;
    for (int k = 0; k < S::kDof; ++k) {
        typename S::Vector step = S::Vector::Zero();
        step[k] = h;
        J.col(k) = S::wrapped(f(S::perturbed(at, step)) - f(S::perturbed(at, -step))) / (2 * h);
    }
    return J;
}

template <class S>
typename S::Matrix inverseOf(const typename S::Matrix& m) {
    return m.ldlt().solve(S::Matrix::Identity());
}

/** Where a closure from anchored pose `a` puts its moving end, in the anchored frame. */
template <class S>
typename S::Pose mapPoseOfU(const typename S::Pose& a, const typename S::Pose& z, bool uIsTo) {
    return uIsTo ? S::compose(a, z) : S::compose(a, S::inverse(z));
}

template <class S>
typename S::Vector residualAfter(const HypothesisT<S>& h, const typename S::Pose& T) {
    const auto u = S::compose(T, h.u);
    return h.uIsTo ? closureResidual<S>(h.a, u, h.z) : closureResidual<S>(u, h.a, h.z);
}

}  // namespace

template <class S>
typename S::Vector closureResidual(const typename S::Pose& from, const typename S::Pose& to,
                                   const typename S::Pose& z) {
    return S::coordinates(S::compose(S::inverse(z), S::compose(S::inverse(from), to)));
}

template <class S>
typename S::Pose impliedTransform(const HypothesisT<S>& h) {
    return S::compose(mapPoseOfU<S>(h.a, h.z, h.uIsTo), S::inverse(h.u));
}

template <class S>
double pairwiseChi2(const HypothesisT<S>& i, const HypothesisT<S>& j,
                    const typename S::Matrix& odometryCov, const typename S::Matrix& mapCov) {
    using Pose = typename S::Pose;
    const Pose d = S::compose(S::inverse(i.u), j.u);
    const Pose m = S::compose(S::inverse(i.a), j.a);
    // e = d^-1 (+) (P_i^-1 (+) P_j): the moved group's own relative pose against the one the
    // two closures imply, P_i = a_i (+) z_i and P_j = a_i (+) m (+) z_j.
    const auto error = [&](const Pose& zi, const Pose& zj, const Pose& d_, const Pose& m_) {
        const Pose Pi = mapPoseOfU<S>(i.a, zi, i.uIsTo);
        const Pose Pj = mapPoseOfU<S>(S::compose(i.a, m_), zj, j.uIsTo);
        return S::coordinates(S::compose(S::inverse(d_), S::compose(S::inverse(Pi), Pj)));
    };
    const auto e = error(i.z, j.z, d, m);
    const auto Ji = jacobian<S>([&](const Pose& p) { return error(p, j.z, d, m); }, i.z);
    const auto Jj = jacobian<S>([&](const Pose& p) { return error(i.z, p, d, m); }, j.z);
    const auto Jd = jacobian<S>([&](const Pose& p) { return error(i.z, j.z, p, m); }, d);
    const auto Jm = jacobian<S>([&](const Pose& p) { return error(i.z, j.z, d, p); }, m);
    const typename S::Matrix Sigma = Ji * i.cov * Ji.transpose() + Jj * j.cov * Jj.transpose() +
                                     Jd * odometryCov * Jd.transpose() +
                                     Jm * mapCov * Jm.transpose();
    return e.dot(Sigma.ldlt().solve(e));
}

template <class S>
double chi2After(const HypothesisT<S>& h, const typename S::Pose& T) {
    const auto r = residualAfter<S>(h, T);
    return r.dot(h.cov.ldlt().solve(r));
}

template <class S>
typename S::Matrix movedPoseCovariance(const typename S::Pose& T, const typename S::Matrix& covT,
                                       const typename S::Pose& u) {
    const auto inverseAt = S::inverse(S::compose(T, u));
    const auto J = jacobian<S>(
        [&](const typename S::Pose& t) {
            return S::coordinates(S::compose(inverseAt, S::compose(t, u)));
        },
        T);
    return J * covT * J.transpose();
}

template <class S>
typename S::Pose fitTransform(const std::vector<HypothesisT<S>>& hs, const typename S::Pose& start,
                              typename S::Matrix* covariance) {
    typename S::Pose T = start;
    typename S::Matrix H = S::Matrix::Identity();
    for (int iteration = 0; iteration < 20; ++iteration) {
        H.setZero();
        typename S::Vector g = S::Vector::Zero();
        for (const auto& h : hs) {
            const typename S::Matrix W = inverseOf<S>(h.cov);
            const auto r = [&](const typename S::Pose& t) { return residualAfter<S>(h, t); };
            const auto J = jacobian<S>(r, T);
            const auto e = r(T);
            H += J.transpose() * W * J;
            g += J.transpose() * W * e;
        }
        const typename S::Vector step = -H.ldlt().solve(g);
        if (!step.allFinite()) break;
        T = S::perturbed(T, step);
        const int nt = S::kTranslationDof;
        if (step.head(nt).norm() < 1e-7 && step.tail(S::kDof - nt).norm() < 1e-9) break;
    }
    if (covariance) *covariance = inverseOf<S>(H);
    return T;
}

#define LODESTONE_CLOSURE_ALGEBRA(S)                                                              \
    template S::Vector closureResidual<S>(const S::Pose&, const S::Pose&, const S::Pose&);        \
    template S::Pose impliedTransform<S>(const HypothesisT<S>&);                                  \
    template double pairwiseChi2<S>(const HypothesisT<S>&, const HypothesisT<S>&,                 \
                                    const S::Matrix&, const S::Matrix&);                          \
    template S::Pose fitTransform<S>(const std::vector<HypothesisT<S>>&, const S::Pose&,          \
                                     S::Matrix*);                                                 \
    template S::Matrix movedPoseCovariance<S>(const S::Pose&, const S::Matrix&, const S::Pose&);  \
    template double chi2After<S>(const HypothesisT<S>&, const S::Pose&);
LODESTONE_CLOSURE_ALGEBRA(PlanarSpace)
LODESTONE_CLOSURE_ALGEBRA(SpatialSpace)
#undef LODESTONE_CLOSURE_ALGEBRA

}  // namespace lodestone::graphslam::relocalization
