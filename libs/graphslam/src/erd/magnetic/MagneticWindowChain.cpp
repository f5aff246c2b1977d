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

/** The query's earlier window being followed back, and what every candidate's search of it
 * shares. */
struct MagneticWindowERD::ChainWindow {
    std::size_t first;  ///< the window's first sample in the query's track
    long tolerance;     ///< [samples] the realignment a window may need, either way
    const Eigen::MatrixX3d& projected;  ///< the window in the noise's eigenbasis
    const magnetic::WindowDisplacementModel& model;
    double logNull;      ///< the building's null of the window (NaN: none)
    double queryTravel;  ///< the query's newest reading's travel (what is left behind)
    /** A target window's evidence, once per window: neighbouring candidates' searches
     * overlap (their relative headings, the fits' priors, differ by little). */
    std::unordered_map<std::uint64_t, magnetic::WindowDisplacementModel::Evidence> seen;
};

/** A candidate followed one window back: its mean evidence near and far over the realigned
 * positions, and the likeliest position (-1: the path ends or leaves its segment). */
struct MagneticWindowERD::ChainStep {
    double meanNear, meanFar;
    long start;
};

bool MagneticWindowERD::chainEvidence(std::vector<Candidate>& all, std::size_t first,
                                      const std::function<bool()>& decided,
                                      double firstNull) const {
    const auto& query = queried().samples();
    const std::size_t newest = first + n_ - 1;
    double bestLog = -INFINITY;
    for (const auto& k : all) bestLog = std::max(bestLog, k.logWeight);
    if (!std::isfinite(bestLog)) return false;
    // Each followed candidate's place on its path, window by window back; the rest are
    // granted the most any followed candidate gained: the posterior of the best is not raised
    // by what was not looked at.
    std::vector<long> start(all.size(), -1);
    for (std::size_t i = 0; i < all.size(); ++i) {
        const auto& k = all[i];
        if (k.logWeight >= bestLog - kChainMargin)
            start[i] = long(k.direction == WindowDirection::Forward ? k.sample + 1 - n_ : k.sample);
    }
    // With the building's null, each earlier window's evidence against the building's windows
    // (its own buildingNull) - as if each window's place were drawn afresh: what makes a quiet
    // walk's chain decisive, and what overstates it where the field's broad part (a level that
    // holds for metres) carries the evidence: docs/results/magnetic-recall.md.
    const bool building = std::isfinite(firstNull);
    bool chained = false;
    for (int j = 1; j < params_.chainWindows; ++j) {
        // The query's window j back, whole and in its segment.
        const std::size_t back = std::size_t(j) * n_;
        if (first < back || query[first - back].segment != query[newest].segment) break;
        const std::size_t f = first - back;
        const double excitation = magnetic::windowExcitation(query, f, n_, params_.noise.sigma);
        // A flat window matches anywhere: under a noise not learnt from the run, against a null
        // as quiet as itself, it is passed over (the candidates followed on through it as the
        // passes ran alike), its evidence none; under a learnt noise, or against the building's
        // windows (a quiet window at a rare level is evidence), its little evidence counts.
        if (!noiseLearnt() && !building &&
            std::min(excitation, mapFrameExcitation(f)) <
                magnetic::chiSquareQuantile(3.0 * double(n_) - 3, params_.quantile)) {
            for (std::size_t i = 0; i < all.size(); ++i) {
                if (start[i] < 0) continue;
                const bool forward = all[i].direction == WindowDirection::Forward;
                start[i] = forward ? start[i] - long(n_) : start[i] + long(n_);
                if (start[i] < 0 || std::size_t(start[i]) + n_ > all[i].track->samples().size())
                    start[i] = -1;
            }
            continue;
        }
        const double spread = std::min(windowSpread(excitation), mapFrameSpread(f));
        const magnetic::WindowDisplacementModel model(basis_, spread, params_.sigmaCross,
                                                      params_.distinctRadius);
        const double logNull = building ? buildingNull(f, model) : NAN;
        if (building && !std::isfinite(logNull)) break;  // (too little path outside the gate)
        const Eigen::MatrixX3d projected = projectedWindow(queried(), f, false);
        // Two passes sigma_cross apart differ in length through the window's turn by that times
        // the turn: the realignment a window may need, at least a sample.
        const double slack = params_.sigmaCross * std::abs(windowTurn(queried(), f)) + params_.step;
        const auto tolerance = static_cast<long>(std::ceil(slack / params_.step));
        ChainWindow window{f, tolerance, projected, model, logNull, query[newest].s, {}};
        double gainNear = 0, gainFar = 0;
        bool any = false;
        for (std::size_t i = 0; i < all.size(); ++i) {
            if (start[i] < 0) continue;
            auto& k = all[i];
            const ChainStep step = followBack(k, start[i], window);
            const double meanNear = step.meanNear, meanFar = step.meanFar;
            const long bestStart = step.start;
            start[i] = bestStart;  // (the path ends, or leaves the segment: followed no further)
            if (bestStart < 0) continue;
            any = true;
            k.logWeight += meanNear;
            k.logFar += std::isfinite(meanFar) ? meanFar : 0.0;
            k.total = -2 * k.logWeight;
            gainNear = std::max(gainNear, meanNear);
            gainFar = std::max(gainFar, std::isfinite(meanFar) ? meanFar : 0.0);
        }
        if (!any) break;
        chained = true;
        for (std::size_t i = 0; i < all.size(); ++i) {
            if (start[i] >= 0) continue;
            all[i].logWeight += gainNear;
            all[i].logFar += gainFar;
            all[i].total = -2 * all[i].logWeight;
        }
    }
    // Decided on the whole chain, not at the first window that tips it: evidence looked at
    // window by window until it crosses the bar crosses it by chance more often.
    if (chained) decided();
    return chained;
}

MagneticWindowERD::ChainStep MagneticWindowERD::followBack(const Candidate& k, long from,
                                                          ChainWindow& w) const {
    const auto& query = queried().samples();
    const auto& stored = k.track->samples();
    const bool forward = k.direction == WindowDirection::Forward;
    const int segment = stored[k.sample].segment;
    const double turnFloor = params_.turnFloorDeg * M_PI / 180;
    // The relative heading of the passes holds along them: this window's fit is the
    // prior. The target a window further back along the path (forward), or further on
    // (walked back).
    const double turnVariance = k.fit.turnVariance + turnFloor * turnFloor;
    const long predicted = forward ? from - long(n_) : from + long(n_);
    // The realignment is a nuisance: its positions weighed alike (their likelihoods
    // averaged, an Occam factor), the window followed on from the likeliest.
    double bestNear = -INFINITY, sumNear = -INFINITY, sumFar = -INFINITY;
    long bestStart = -1, positions = 0;
    const auto logAdd = [](double a, double b) {
        if (a == -INFINITY) return b;
        if (b == -INFINITY) return a;
        return std::max(a, b) + std::log1p(std::exp(-std::abs(a - b)));
    };
    for (long s = predicted - w.tolerance; s <= predicted + w.tolerance; ++s) {
        if (s < 0 || std::size_t(s) + n_ > stored.size()) continue;
        const auto t = static_cast<std::size_t>(s);
        if (stored[t].segment != segment || stored[t + n_ - 1].segment != segment ||
            !leftBehind(stored[t + n_ - 1], w.queryTravel))
            continue;
        const std::uint64_t key = projectionKey(*k.track, t, !forward);
        auto it = w.seen.find(key);
        if (it == w.seen.end()) {
            Candidate c = k;
            c.fit = magnetic::compareWindows(query, w.first, stored, t, n_, k.direction,
                                             params_.noise, k.fit.turn, turnVariance);
            it = w.seen.emplace(key, w.model.evidenceProjected(
                                       projectedResiduals(c, t, w.projected),
                                       nearRadius(windowTurn(*k.track, t))))
                     .first;
        }
        const auto& e = it->second;
        const double null = std::isfinite(w.logNull) ? e.logUnrelated - w.logNull : 0.0;
        ++positions;
        sumNear = logAdd(sumNear, e.logNear + null);
        sumFar = logAdd(sumFar, e.logFar + null);
        if (e.logNear + null > bestNear) {
            bestNear = e.logNear + null;
            bestStart = s;
        }
    }
    const double meanNear = sumNear - std::log(double(std::max(positions, 1L)));
    const double meanFar = sumFar - std::log(double(std::max(positions, 1L)));
    return {meanNear, meanFar, bestStart};
}

}  // namespace lodestone::graphslam
