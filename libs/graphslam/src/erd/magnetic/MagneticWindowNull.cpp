// MagneticWindowERD with null_model = building: "no earlier place in the gate" weighed as the
// query read at a place of the building outside the gate taken at random - the mean of its
// likelihood against windows of the path so far outside the gate, each aligned as a candidate
// is. A window that looks like many places of this building (a quiet stretch at the building's
// usual level, the field of one of a row of steel beams) is then no evidence of any one place,
// however well it fits one; a window that looks like few is strong evidence, however quiet. No
// amplitude is assumed: the building's own field says how often a look-alike occurs.
#include <lodestone/graphslam/erd/magnetic/MagneticWindowERD.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace lodestone::graphslam {

using magnetic::WindowDirection;

namespace {
// Windows of the path per direction the mean is taken over: a length scale apart up to this
// many (560 m of path at 0.28 m), the stride growing beyond, so that a query's cost stays
// bounded on an hour's walk. Sparser, a sharp look-alike falls between the windows taken and
// the null reads too low (a window every metre: a field never seen before was closed).
constexpr std::size_t kMaxNullWindows = 2000;
// Fewer than this and the path is too short to say what the building looks like.
constexpr std::size_t kMinNullWindows = 16;
}  // namespace

double MagneticWindowERD::buildingNull(std::size_t first,
                                       const magnetic::WindowDisplacementModel& model) const {
    const auto& query = queried().samples();
    const std::size_t newest = first + n_ - 1;
    const auto qNode = static_cast<TNodeID>(query[newest].node);
    const Eigen::Vector2d here = positionAtSample(queried(), newest);
    const Eigen::MatrixX3d projected = projectedWindow(queried(), first, false);
    // Windows a length scale apart sample the field's variation along the path.
    const auto minStride = static_cast<std::size_t>(
        std::max(1.0, std::round(params_.lengthScale / params_.step)));
    double maxLog = -INFINITY;
    std::vector<double> terms;
    const auto average = [&](const magnetic::SupernodeTrack& track, WindowDirection direction) {
        const bool forward = direction == WindowDirection::Forward;
        const auto& stored = track.samples();
        // The windows left behind (min_travel_gap), as candidates are: a prefix of the track
        // (a loaded map's readings first, then the run's in travel order).
        const auto end = static_cast<std::size_t>(
            std::partition_point(stored.begin(), stored.end(),
                                 [&](const magnetic::TrackSample& t) {
                                     return leftBehind(t, query[newest].s);
                                 }) -
            stored.begin());
        if (end < n_) return;
        const std::size_t stride = std::max(minStride, (end - n_) / kMaxNullWindows + 1);
        for (std::size_t t = 0; t + n_ <= end; t += stride) {
            if (stored[t].segment != stored[t + n_ - 1].segment) continue;
            Candidate c;
            c.track = &track;
            c.direction = direction;
            c.sample = forward ? t + n_ - 1 : t;
            // The places in the gate are the other hypotheses: the null is a place outside it,
            // its relative heading as the graph has it (the field's direction holds in the
            // building, wherever the place), aligned as a candidate is.
            const Prior p = priorAt(track, c.sample, qNode, here);
            if (p.gate2 <= params_.gateChi2) continue;
            c.fit = magnetic::compareWindows(query, first, stored, t, n_, direction, params_.noise,
                                             p.turn, p.turnVariance);
            const auto e = model.evidenceProjected(projectedResiduals(c, t, projected),
                                                   nearRadius(windowTurn(track, t)));
            const double near = e.logNear + e.logUnrelated;
            const double far = e.logFar + e.logUnrelated;
            const double term = std::isfinite(far) ? std::max(near, far) +
                                                         std::log1p(std::exp(-std::abs(near - far)))
                                                   : near;
            terms.push_back(term);
            maxLog = std::max(maxLog, term);
        }
    };
    average(queried(), WindowDirection::Forward);
    average(mirrored(), WindowDirection::Backward);
    if (terms.size() < kMinNullWindows || !std::isfinite(maxLog)) return NAN;
    double sum = 0;
    for (const double t : terms) sum += std::exp(t - maxLog);
    return maxLog + std::log(sum / double(terms.size()));
}

double MagneticWindowERD::weighAgainstBuilding(std::vector<Candidate>& all, std::size_t first,
                                               const magnetic::WindowDisplacementModel& model) const {
    const double logNull = buildingNull(first, model);
    for (auto& k : all) {
        if (!std::isfinite(k.logWeight)) continue;
        const double shift = std::isfinite(logNull) ? -logNull : -k.logUnrelated;
        k.logWeight += shift;
        k.logFar += shift;
        k.total = -2 * k.logWeight;
    }
    return logNull;
}

}  // namespace lodestone::graphslam
