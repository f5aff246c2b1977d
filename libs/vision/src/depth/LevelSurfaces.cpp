#include <lodestone/vision/depth/LevelSurfaces.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>

namespace lodestone::vision {

namespace {

/** Two unit vectors completing `u` to an orthonormal basis: the up's two tilt axes. */
void tiltAxes(const Eigen::Vector3d& u, Eigen::Vector3d& e1, Eigen::Vector3d& e2) {
    const Eigen::Vector3d a =
        std::abs(u.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    e1 = u.cross(a).normalized();
    e2 = u.cross(e1);
}

struct Candidate {
    Eigen::Vector3d p;
    double depthSigma;  // along the ray, at the point's depth
    int surface;        // -1: none
};


/** A candidate's sigma along the up: the depth noise along the ray projected on it (a grazing
 * floor's points err mostly along the floor) and the surface's roughness. */
double pointSigma(const Candidate& c, const Eigen::Vector3d& up, double roughness) {
    const double along = c.depthSigma * std::abs(up.dot(c.p)) / c.p.z();
    return std::hypot(along, roughness);
}

/** Candidates: normals (unit, facing the camera) along the up within the gate - a floor's face
 * up, a ceiling's down; their mean normal (turned to the up) into `meanNormal`. */
std::vector<Candidate> levelCandidates(const DepthCloud& cloud, const Eigen::Vector3d& up,
                                       double cosGate, Eigen::Vector3d& meanNormal) {
    std::vector<Candidate> pts;
    meanNormal.setZero();
    for (std::size_t k = 0; k < cloud.size(); ++k) {
        const Eigen::Vector3d n = cloud.normals.col(static_cast<Eigen::Index>(k)).cast<double>();
        const double c = n.dot(up);
        if (std::abs(c) < cosGate || !n.allFinite()) continue;
        const Eigen::Vector3d p = cloud.points.col(static_cast<Eigen::Index>(k)).cast<double>();
        if (!p.allFinite() || !(p.z() > 0)) continue;
        pts.push_back({p, static_cast<double>(cloud.sigma(static_cast<Eigen::Index>(k))), -1});
        meanNormal += c > 0 ? n : Eigen::Vector3d(-n);
    }
    return pts;
}

/** Surfaces: the candidates' heights below the camera, sorted, split where they jump by more
 * than `separation`; a run of minPoints whose mean height is minHeight at least is a surface
 * (its candidates marked). Each surface's height. */
std::vector<double> splitByHeight(std::vector<Candidate>& pts, const Eigen::Vector3d& up,
                                  const LevelSurfaceParams& params) {
    std::vector<std::size_t> order(pts.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    const auto heightOf = [&](const Candidate& c) { return -up.dot(c.p); };
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return heightOf(pts[a]) < heightOf(pts[b]); });
    std::vector<double> heights;  // each surface's start height (camera above it)
    std::size_t begin = 0;
    for (std::size_t i = 1; i <= order.size(); ++i) {
        if (i < order.size() &&
            heightOf(pts[order[i]]) - heightOf(pts[order[i - 1]]) <= params.separation)
            continue;
        if (i - begin >= params.minPoints) {
            double mean = 0;
            for (std::size_t j = begin; j < i; ++j) mean += heightOf(pts[order[j]]);
            mean /= static_cast<double>(i - begin);
            if (std::abs(mean) >= params.minHeight) {
                for (std::size_t j = begin; j < i; ++j)
                    pts[order[j]].surface = static_cast<int>(heights.size());
                heights.push_back(mean);
            }
        }
        begin = i;
    }
    return heights;
}

/** Each candidate to the surface it lies on within 3 sigma, if any (a floor's point the first
 * split left with a table, or a wall's foot among the floor's). */
void regate(std::vector<Candidate>& pts, const Eigen::Vector3d& up,
            const std::vector<double>& heights, double roughness) {
    for (Candidate& c : pts) {
        c.surface = -1;
        double best = 3;
        for (std::size_t s = 0; s < heights.size(); ++s) {
            const double z = std::abs(up.dot(c.p) + heights[s]) / pointSigma(c, up, roughness);
            if (z <= best) {
                best = z;
                c.surface = static_cast<int>(s);
            }
        }
    }
}
}  // namespace

std::optional<LevelSurfaces> fitLevelSurfaces(const DepthCloud& cloud,
                                              const Eigen::Vector3d& expectedUp,
                                              const LevelSurfaceParams& params) {
    if (cloud.size() == 0 || !(expectedUp.norm() > 0)) return std::nullopt;
    Eigen::Vector3d up = expectedUp.normalized();
    Eigen::Vector3d meanNormal = Eigen::Vector3d::Zero();
    std::vector<Candidate> pts = levelCandidates(cloud, up, std::cos(params.normalGate), meanNormal);
    if (pts.size() < params.minPoints) return std::nullopt;
    up = meanNormal.normalized();

    std::vector<double> heights = splitByHeight(pts, up, params);
    if (heights.empty()) return std::nullopt;

    // One weighted least-squares fit: residual r = up . p + h_s for a point of surface s, its
    // sigma the depth noise along the ray projected on the up (a grazing floor's points err
    // mostly along the floor) and the surface's roughness. Unknowns: the up's two tilts, each h.
    const int m = static_cast<int>(heights.size());
    const int dof = 2 + m;
    Eigen::MatrixXd H(dof, dof);
    double chi2 = 0;
    std::size_t used = 0;
    for (int round = 0; round < 2; ++round) {
        for (int iteration = 0; iteration < 4; ++iteration) {
            Eigen::Vector3d e1, e2;
            tiltAxes(up, e1, e2);
            H.setZero();
            Eigen::VectorXd g = Eigen::VectorXd::Zero(dof);
            chi2 = 0;
            used = 0;
            for (const Candidate& c : pts) {
                if (c.surface < 0) continue;
                const double w = 1 / std::pow(pointSigma(c, up, params.roughness), 2);
                const double r = up.dot(c.p) + heights[static_cast<std::size_t>(c.surface)];
                Eigen::VectorXd J = Eigen::VectorXd::Zero(dof);
                J(0) = e1.dot(c.p);
                J(1) = e2.dot(c.p);
                J(2 + c.surface) = 1;
                H.selfadjointView<Eigen::Lower>().rankUpdate(J, w);
                g += w * r * J;
                chi2 += w * r * r;
                ++used;
            }
            H = H.selfadjointView<Eigen::Lower>();
            const Eigen::LDLT<Eigen::MatrixXd> ldlt(H);
            if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0))
                return std::nullopt;
            const Eigen::VectorXd step = -ldlt.solve(g);
            if (!step.allFinite()) return std::nullopt;
            up = (up + step(0) * e1 + step(1) * e2).normalized();
            for (int s = 0; s < m; ++s) heights[static_cast<std::size_t>(s)] += step(2 + s);
        }
        if (round == 1) break;
        regate(pts, up, heights, params.roughness);
    }
    // Surfaces left with too few points are dropped from the result (their points still
    // helped the up); their counts:
    std::vector<std::size_t> counts(static_cast<std::size_t>(m), 0);
    for (const Candidate& c : pts)
        if (c.surface >= 0) ++counts[static_cast<std::size_t>(c.surface)];
    const double scale = std::max(1.0, chi2 / std::max<double>(1, static_cast<double>(used) - dof));
    const Eigen::MatrixXd C = H.inverse() * scale;
    if (!C.allFinite()) return std::nullopt;
    const double tilt2 = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(C.topLeftCorner<2, 2>())
                             .eigenvalues()
                             .maxCoeff();
    const double upSigma = std::sqrt(std::max(0.0, tilt2));
    if (!(upSigma <= params.maxUpSigma)) return std::nullopt;
    LevelSurfaces out;
    out.up = up;
    out.upSigma = std::max(upSigma, params.minUpSigma);
    for (int s = 0; s < m; ++s) {
        if (counts[static_cast<std::size_t>(s)] < params.minPoints) continue;
        out.surfaces.push_back({heights[static_cast<std::size_t>(s)],
                                std::max(std::sqrt(C(2 + s, 2 + s)), params.minHeightSigma),
                                counts[static_cast<std::size_t>(s)]});
    }
    if (out.surfaces.empty()) return std::nullopt;
    std::sort(out.surfaces.begin(), out.surfaces.end(),
              [](const LevelSurface& a, const LevelSurface& b) { return a.points > b.points; });
    return out;
}

}  // namespace lodestone::vision
