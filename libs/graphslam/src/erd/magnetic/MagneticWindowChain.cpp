// MagneticWindowERD: a query left undecided for want of field gathers the windows before it, in
// sequence (chain_windows). Each candidate's place is followed back along its own path, window by
// window, each earlier window aligned again near where the one after it placed it - a walker's
// passes of one place differ in length through turns, which one rigid long window could not
// follow - and the earlier windows' evidence (near and beside, against unrelated places) is added
// to the candidate's own.
#include <lodestone/graphslam/erd/magnetic/MagneticWindowERD.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <unordered_map>

namespace lodestone::graphslam {

using magnetic::WindowDirection;

namespace {
// Candidates further below the best than this (log) are not followed back: their weight is
// negligible unless earlier windows favour them by as much, which is granted them (below).
constexpr double kChainMargin = 25.0;
}  // namespace

bool MagneticWindowERD::chainEvidence(std::vector<Candidate>& all, std::size_t first,
                                      const std::function<bool()>& decided) const {
    const auto& query = queried().samples();
    const std::size_t newest = first + n_ - 1;
    double bestLog = -INFINITY;
    for (const auto& k : all) bestLog = std::max(bestLog, k.logWeight);
    if (!std::isfinite(bestLog)) return false;
    const double turnFloor = params_.turnFloorDeg * M_PI / 180;
    // Each followed candidate's place on its path, window by window back; the rest are
    // granted the most any followed candidate gained: the posterior of the best is not raised
    // by what was not looked at.
    std::vector<long> start(all.size(), -1);
    for (std::size_t i = 0; i < all.size(); ++i) {
        const auto& k = all[i];
        if (k.logWeight >= bestLog - kChainMargin)
            start[i] = long(k.direction == WindowDirection::Forward ? k.sample + 1 - n_ : k.sample);
    }
    bool chained = false;
    for (int j = 1; j < params_.chainWindows; ++j) {
        // The query's window j back, whole and in its segment.
        const std::size_t back = std::size_t(j) * n_;
        if (first < back || query[first - back].segment != query[newest].segment) break;
        const std::size_t f = first - back;
        const double spread = std::min(
            windowSpread(magnetic::windowExcitation(query, f, n_, params_.noise.sigma)),
            mapFrameSpread(f));
        const magnetic::WindowDisplacementModel model(basis_, spread, params_.sigmaCross,
                                                      params_.distinctRadius);
        const Eigen::MatrixX3d projected = projectedWindow(queried(), f, false);
        // Two passes sigma_cross apart differ in length through the window's turn by that times
        // the turn: the realignment a window may need, at least a sample.
        const double slack = params_.sigmaCross * std::abs(windowTurn(queried(), f)) + params_.step;
        const auto tolerance = static_cast<long>(std::ceil(slack / params_.step));
        double gainNear = 0, gainFar = 0;
        bool any = false;
        // A target window's evidence, once per window: neighbouring candidates' searches
        // overlap (their relative headings, the fits' priors, differ by little).
        std::unordered_map<std::uint64_t, magnetic::WindowDisplacementModel::Evidence> seen;
        for (std::size_t i = 0; i < all.size(); ++i) {
            if (start[i] < 0) continue;
            auto& k = all[i];
            const auto& stored = k.track->samples();
            const bool forward = k.direction == WindowDirection::Forward;
            const int segment = stored[k.sample].segment;
            // The relative heading of the passes holds along them: this window's fit is the
            // prior. The target a window further back along the path (forward), or further on
            // (walked back).
            const double turnVariance = k.fit.turnVariance + turnFloor * turnFloor;
            const long predicted = forward ? start[i] - long(n_) : start[i] + long(n_);
            double bestNear = -INFINITY, bestFar = -INFINITY;
            long bestStart = -1;
            for (long s = predicted - tolerance; s <= predicted + tolerance; ++s) {
                if (s < 0 || std::size_t(s) + n_ > stored.size()) continue;
                const auto t = static_cast<std::size_t>(s);
                if (stored[t].segment != segment || stored[t + n_ - 1].segment != segment ||
                    !leftBehind(stored[t + n_ - 1], query[newest].s))
                    continue;
                const std::uint64_t key = projectionKey(*k.track, t, !forward);
                auto it = seen.find(key);
                if (it == seen.end()) {
                    Candidate c = k;
                    c.fit = magnetic::compareWindows(query, f, stored, t, n_, k.direction,
                                                     params_.noise, k.fit.turn, turnVariance);
                    it = seen.emplace(key, model.evidenceProjected(
                                               projectedResiduals(c, t, projected),
                                               nearRadius(windowTurn(*k.track, t))))
                             .first;
                }
                const auto& e = it->second;
                if (e.logNear > bestNear) {
                    bestNear = e.logNear;
                    bestFar = e.logFar;
                    bestStart = s;
                }
            }
            start[i] = bestStart;  // (the path ends, or leaves the segment: followed no further)
            if (bestStart < 0) continue;
            any = true;
            k.logWeight += bestNear;
            k.logFar += std::isfinite(bestFar) ? bestFar : 0.0;
            k.total = -2 * k.logWeight;
            gainNear = std::max(gainNear, bestNear);
            gainFar = std::max(gainFar, std::isfinite(bestFar) ? bestFar : 0.0);
        }
        if (!any) break;
        chained = true;
        for (std::size_t i = 0; i < all.size(); ++i) {
            if (start[i] >= 0) continue;
            all[i].logWeight += gainNear;
            all[i].logFar += gainFar;
            all[i].total = -2 * all[i].logWeight;
        }
        if (decided()) break;
    }
    return chained;
}

}  // namespace lodestone::graphslam
