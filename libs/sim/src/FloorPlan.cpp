#include <lodestone/sim/FloorPlan.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lodestone::sim {

namespace {
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() * b.y() - a.y() * b.x();
}

double pointSegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                            const Eigen::Vector2d& b) {
    const Eigen::Vector2d ab = b - a;
    const double len2 = ab.squaredNorm();
    const double s = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (a + s * ab - p).norm();
}
}  // namespace

double segmentDistance(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1,
                       const Eigen::Vector2d& q0, const Eigen::Vector2d& q1) {
    const Eigen::Vector2d r = p1 - p0, s = q1 - q0;
    const double denom = cross(r, s);
    if (std::abs(denom) > 1e-15) {
        const double t = cross(q0 - p0, s) / denom, u = cross(q0 - p0, r) / denom;
        if (t >= 0 && t <= 1 && u >= 0 && u <= 1) return 0.0;
    }
    return std::min({pointSegmentDistance(p0, q0, q1), pointSegmentDistance(p1, q0, q1),
                     pointSegmentDistance(q0, p0, p1), pointSegmentDistance(q1, p0, p1)});
}

void FloorPlan::addWall(const Wall& wall) { walls_.push_back(wall); }

std::optional<WallHit> FloorPlan::castRay(const Eigen::Vector2d& origin,
                                          const Eigen::Vector2d& direction, double tMin,
                                          double tMax) const {
    std::optional<WallHit> best;
    double bestT = tMax;
    for (std::size_t i = 0; i < walls_.size(); ++i) {
        const Wall& w = walls_[i];
        const Eigen::Vector2d s = w.b - w.a;
        const double denom = cross(direction, s);
        if (std::abs(denom) < 1e-12) continue;  // parallel
        const Eigen::Vector2d d = w.a - origin;
        const double t = cross(d, s) / denom;
        const double v = cross(d, direction) / denom;  // position along the wall, 0..1
        if (t <= tMin || t > bestT || v < 0 || v > 1) continue;
        bestT = t;
        const double len = s.norm();
        const Eigen::Vector2d normal(-s.y() / len, s.x() / len);
        const double cosInc = std::abs(normal.dot(direction)) / direction.norm();
        best = WallHit{t, static_cast<int>(i), v * len, cosInc};
    }
    return best;
}

double FloorPlan::clearance(const Eigen::Vector2d& p) const {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& w : walls_) best = std::min(best, pointSegmentDistance(p, w.a, w.b));
    return best;
}

bool FloorPlan::blocks(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double clearance) const {
    for (const auto& w : walls_) {
        if (segmentDistance(a, b, w.a, w.b) < clearance) return true;
    }
    return false;
}

Eigen::Vector2d FloorPlan::minCorner() const {
    Eigen::Vector2d m(std::numeric_limits<double>::infinity(),
                      std::numeric_limits<double>::infinity());
    for (const auto& w : walls_) m = m.cwiseMin(w.a).cwiseMin(w.b);
    return m;
}

Eigen::Vector2d FloorPlan::maxCorner() const {
    Eigen::Vector2d m(-std::numeric_limits<double>::infinity(),
                      -std::numeric_limits<double>::infinity());
    for (const auto& w : walls_) m = m.cwiseMax(w.a).cwiseMax(w.b);
    return m;
}

}  // namespace lodestone::sim
