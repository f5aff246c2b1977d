// MagneticWindowERD: the candidates' weights - the position prior normalized over them, their
// fit against the null on the same line or weighed by the passes' distance - and the posterior
// of the best place against every other place, the passes beside and the null.
#include <lodestone/graphslam/erd/magnetic/MagneticWindowERD.h>

#include <algorithm>
#include <cmath>

namespace lodestone::graphslam {

using magnetic::WindowDirection;

double MagneticWindowERD::logPriorNormalizer(const std::vector<Candidate>& all) {
    // The position prior normalized over the candidates (both directions of every sample).
    double logZ = -INFINITY;
    for (const auto& k : all) {
        const double v = -0.5 * k.gate2;
        logZ = std::max(logZ, v) + std::log1p(std::exp(-std::abs(logZ - v)));
    }
    return logZ;
}

void MagneticWindowERD::weighSameLine(const Candidate& best, std::vector<Candidate>& all,
                                      std::size_t first,
                                      const magnetic::WindowNullModel& null) const {
    const double logZ = logPriorNormalizer(all);
    // A candidate that fits worse than this beyond the fit test weighs nothing next to one
    // that passes it: its likelihood ratio is not worth computing.
    const double negligible =
        magnetic::chiSquareQuantile(3.0 * double(n_), 1 - 1e-12) + best.fit.chi2;
    for (auto& k : all) {
        if (k.fit.chi2 > negligible) continue;
        k.logWeight = null.logLikelihoodRatio(residuals(k, first)) -
                      0.5 * (k.gate2 + k.fit.turnPriorChi2) - logZ;
    }
}

void MagneticWindowERD::weighDisplaced(std::vector<Candidate>& all, std::size_t first,
                                       const magnetic::WindowDisplacementModel& model,
                                       double logNull) const {
    const double logZ = logPriorNormalizer(all);
    // A candidate whose differences fail the fit test by this much even at distinct_radius
    // apart weighs nothing (its weight as a pass further beside is left out with it).
    const double hopeless = magnetic::chiSquareQuantile(3.0 * double(n_), 1 - 1e-12);
    const Eigen::MatrixX3d queryProjected = projectedWindow(queried(), first, false);
    for (auto& k : all) {
        k.fitStat = model.chi2LowerBound(k.fit.chi2 - k.fit.turnPriorChi2, params_.distinctRadius);
        k.total = INFINITY;
        if (k.fitStat > hopeless) continue;
        const std::size_t start =
            k.direction == WindowDirection::Forward ? k.sample + 1 - n_ : k.sample;
        const auto e = model.evidenceProjected(projectedResiduals(k, start, queryProjected),
                                               nearRadius(windowTurn(*k.track, start)));
        const double prior = -0.5 * (k.gate2 + k.fit.turnPriorChi2) - logZ;
        const double null = std::isfinite(logNull) ? e.logUnrelated - logNull : 0.0;
        k.logWeight = e.logNear + null + prior;
        k.logFar = e.logFar + null + prior;
        k.logUnrelated = e.logUnrelated;
        k.nearDelta2 = e.nearDelta2;
        k.fitStat = e.chi2AtRadius;
        k.total = -2 * k.logWeight;
    }
}

double MagneticWindowERD::placePosterior(const Candidate& best,
                                         const std::vector<Candidate>& all) const {
    double maxLog = std::log(params_.nullOdds);
    for (const auto& k : all) maxLog = std::max({maxLog, k.logWeight, k.logFar});

    const auto& b = best.track->samples()[best.sample];
    double same = 0, rest = std::exp(std::log(params_.nullOdds) - maxLog);
    for (const auto& k : all) {
        if (std::isfinite(k.logFar)) rest += std::exp(k.logFar - maxLog);
        if (!std::isfinite(k.logWeight)) continue;
        const double w = std::exp(k.logWeight - maxLog);
        // Positions compare within a segment and across joined ones (a loaded map's sessions,
        // a relocated segment): the passes of one place there are one place.
        const bool samePlace = sameFrame(k.track->samples()[k.sample].segment, b.segment) &&
                               (k.position - best.position).norm() <= params_.distinctRadius;
        (samePlace ? same : rest) += w;
    }
    return same / (same + rest);
}

}  // namespace lodestone::graphslam
