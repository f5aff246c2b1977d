// MagneticWindowERD: closures made from accepted windows - at once when they continue a
// confirmed match, else once a later window that does not overlap them agrees.
#include <lodestone/graphslam/erd/magnetic/MagneticWindowERD.h>

#include <algorithm>
#include <cmath>

namespace lodestone::graphslam {

using magnetic::WindowDirection;

std::optional<MagneticWindowERD::Closure> MagneticWindowERD::measureClosure(
    const Candidate& best, const std::vector<Candidate>& all, std::size_t first) const {
    const auto& query = queried().samples();
    const auto& samples = best.track->samples();
    const std::size_t newest = first + n_ - 1;
    const auto qNode = static_cast<TNodeID>(query[newest].node);
    const int tSegment = samples[best.sample].segment;
    // Along the target's path the fit's curvature over neighbouring samples (same direction)
    // says how sharply the field places the window: chi2 = -2 log L, information = curvature / 2.
    double fitAt[2] = {NAN, NAN};
    for (const auto& k : all) {
        if (k.direction != best.direction || k.track != best.track) continue;
        if (k.sample + 1 == best.sample) fitAt[0] = k.total;
        if (k.sample == best.sample + 1) fitAt[1] = k.total;
    }
    double sigmaAlong2 =
        params_.sigmaAlongFloor * params_.sigmaAlongFloor + params_.step * params_.step / 12;
    // The fit's minimum between samples (the parabola's vertex through the three): without it
    // every closure between two passes carries the same fraction of a step, as their sample
    // grids lie (a bias, not noise: 0.015 m on each of a corridor lap's closures).
    double between = 0;
    if (std::isfinite(fitAt[0]) && std::isfinite(fitAt[1])) {
        const double curvature =
            (fitAt[0] - 2 * best.total + fitAt[1]) / (params_.step * params_.step);
        sigmaAlong2 += curvature > 0 ? 2.0 / curvature : INFINITY;
        if (curvature > 0)
            between = std::clamp((fitAt[0] - fitAt[1]) / (2 * curvature * params_.step),
                                 -params_.step / 2, params_.step / 2);
    } else {
        sigmaAlong2 += params_.step * params_.step;
    }
    if (!std::isfinite(sigmaAlong2)) return std::nullopt;
    const double sigmaCross2 = params_.sigmaCross * params_.sigmaCross;
    if (params_.passDisplacement) {
        // Two passes beside each other place the robot off along the path too, in proportion
        // to their distance (which the closure does not estimate: its across sigma stays the
        // platform's sigma_cross - the field's own posterior of the distance, about 0.03 m,
        // held 0.13-0.24 m RMS of across error on Kok's walks; README). In a turn the arcs differ
        // in length by the distance times the turn, and the fit, aligning the windows' middles, is
        // off by half of that (nearRadius). Anywhere, the stretch that best aligns two lines of an
        // isotropic field moves by the distance times the ratio of its cross- to along-path
        // gradients summed over the window: to first order of variance (sum of the kernel's
        // correlations) / (3 n) per unit distance squared.
        const std::size_t start =
            best.direction == WindowDirection::Forward ? best.sample + 1 - n_ : best.sample;
        const double turn = windowTurn(*best.track, start);
        sigmaAlong2 += sigmaCross2 * (turn * turn / 4 + correlated_samples_ / (3.0 * double(n_)));
    }
    // The query node's place on the target's path: its travel past the newest reading, the
    // same way along (forward) or back (backward).
    const double ahead = path_.travel[qNode] - query[newest].s;
    const double sBest = samples[best.sample].s + between;
    const double sTarget = sBest + (best.direction == WindowDirection::Forward ? ahead : -ahead);
    const auto it = std::upper_bound(path_.travel.begin(), path_.travel.end(), sTarget);
    if (it == path_.travel.begin() || it == path_.travel.end()) return std::nullopt;
    const auto k = static_cast<TNodeID>(it - path_.travel.begin() - 1);
    if (path_.segment[k] != tSegment || path_.segment[k + 1] != tSegment || k + 1 > qNode)
        return std::nullopt;
    const auto e = m_graph->edges.find({k, k + 1});
    if (e == m_graph->edges.end()) return std::nullopt;
    const auto& d = e->second.mean;
    const double span = path_.travel[k + 1] - path_.travel[k];
    const double frac = span > 0 ? (sTarget - path_.travel[k]) / span : 0.0;
    const double turnSigma = params_.turnFloorDeg * M_PI / 180;
    mrpt::poses::CPosePDFGaussian z;
    z.mean = mrpt::poses::CPose2D(frac * d.x(), frac * d.y(), frac * d.yaw() + best.fit.turn);
    const Eigen::Matrix2d S = alongAcross(d, sigmaAlong2, sigmaCross2);
    z.cov.setZero();
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) z.cov(r, c) = S(r, c);
    z.cov(2, 2) = best.fit.turnVariance + turnSigma * turnSigma;
    Closure c;
    c.target = k;
    c.query = qNode;
    c.z = z;
    c.positionCov = S;
    c.score = -best.fit.chi2 / (3.0 * double(n_));
    c.direction = best.direction;
    c.sQuery = query[newest].s;
    c.sTarget = sBest;
    c.targetSegment = tSegment;
    return c;
}

bool MagneticWindowERD::agree(const Closure& earlier, const Closure& later) const {
    if (earlier.direction != later.direction || earlier.targetSegment != later.targetSegment)
        return false;
    // The later query's place on the earlier match's target path, travelled on the same way
    // (forward) or back (backward).
    const double moved = later.sQuery - earlier.sQuery;
    const double predicted =
        earlier.sTarget + (earlier.direction == WindowDirection::Forward ? moved : -moved);
    return std::abs(predicted - later.sTarget) <= params_.distinctRadius;
}

bool MagneticWindowERD::confirm(const Closure& c) {
    if (!params_.confirm) return commit(c);
    // Continuing a confirmed match: no new evidence needed.
    if (confirmed_ && c.sQuery - confirmed_->sQuery <= 2 * params_.window &&
        agree(*confirmed_, c)) {
        confirmed_ = c;
        return commit(c);
    }
    // Forget what can no longer be confirmed (more than two windows back).
    while (!pending_.empty() && c.sQuery - pending_.front().sQuery > 2 * params_.window)
        pending_.pop_front();
    // A new match is confirmed by an earlier accepted window that does not overlap it (an
    // independent stretch of field) and places the robot consistently.
    for (auto& e : pending_) {
        if (c.sQuery - e.sQuery < params_.window || !agree(e, c)) continue;
        ++stats_.confirmed;
        if (commit(e) && e.truthRecord) truth_queries_[*e.truthRecord].stage = TruthStage::Closed;
        pending_.clear();
        confirmed_ = c;
        return commit(c);
    }
    pending_.push_back(c);
    return false;
}

bool MagneticWindowERD::commit(const Closure& c) {
    if (c.sQuery - last_closure_ + 1e-9 < params_.closureEvery) return false;
    registerClosure(c.target, c.query, planarConstraint(c.z), stats_.edges, false, c.score);
    // The query node is now known as well as the closure says (in the map frame).
    path_.pinClosure(c.query, m_graph->nodes.at(c.target).yaw(), c.positionCov, c.z.cov(2, 2));
    last_closure_ = c.sQuery;
    ++stats_.edges;
    ++(c.direction == WindowDirection::Forward ? stats_.forward : stats_.backward);
    return true;
}

}  // namespace lodestone::graphslam
