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

double MagneticWindowERD::buildingNull(const std::vector<NullWindow>& windows) const {
    // windows[0] is the newest; windows[j] the query's window j back. A place of the path is
    // followed back with it, window by window (forward: back along its path; walked back: on
    // along it): under the null the query's stretch is one stretch of the building, so its
    // windows' likelihoods multiply place by place before they are averaged over places.
    const auto& query = queried().samples();
    const std::size_t newest = windows.front().first + n_ - 1;
    const auto qNode = static_cast<TNodeID>(query[newest].node);
    const Eigen::Vector2d here = positionAtSample(queried(), newest);
    std::vector<Eigen::MatrixX3d> projected;
    for (const auto& w : windows) projected.push_back(projectedWindow(queried(), w.first, false));
    // Windows a length scale apart sample the field's variation along the path.
    const auto minStride = static_cast<std::size_t>(
        std::max(1.0, std::round(params_.lengthScale / params_.step)));
    const auto reach = (windows.size() - 1) * n_;  // how far a place is followed
    double maxLog = -INFINITY;
    std::vector<double> terms;
    const auto average = [&](const magnetic::SupernodeTrack& track, WindowDirection direction) {
        const bool forward = direction == WindowDirection::Forward;
        const auto& stored = track.samples();
        std::size_t end = 0;  // the windows left behind (min_travel_gap), as candidates are
        while (end < stored.size() && leftBehind(stored[end], query[newest].s)) ++end;
        if (end < n_ + reach) return;
        const std::size_t stride = std::max(minStride, (end - n_ - reach) / kMaxNullWindows + 1);
        for (std::size_t t0 = forward ? reach : 0; t0 + n_ + (forward ? 0 : reach) <= end;
             t0 += stride) {
            const std::size_t from = forward ? t0 - reach : t0, to = from + reach + n_ - 1;
            if (stored[from].segment != stored[to].segment) continue;
            // The places in the gate are the other hypotheses: the null is a place outside it.
            if (priorAt(track, forward ? t0 + n_ - 1 : t0, qNode, here).gate2 <= params_.gateChi2)
                continue;
            double sum = 0;
            for (std::size_t j = 0; j < windows.size(); ++j) {
                // Aligned as a candidate is.
                const std::size_t t = forward ? t0 - j * n_ : t0 + j * n_;
                Candidate c;
                c.track = &track;
                c.direction = direction;
                c.sample = forward ? t + n_ - 1 : t;
                // Its relative heading as the graph has it, as a candidate's is: the field's
                // direction holds in the building, wherever the place.
                const std::size_t qNewest = windows[j].first + n_ - 1;
                const Prior p = priorAt(track, c.sample,
                                        static_cast<TNodeID>(query[qNewest].node),
                                        positionAtSample(queried(), qNewest));
                c.fit = magnetic::compareWindows(query, windows[j].first, stored, t, n_,
                                                 direction, params_.noise, p.turn,
                                                 p.turnVariance);
                const auto e = windows[j].model->evidenceProjected(
                    projectedResiduals(c, t, projected[j]), nearRadius(windowTurn(track, t)));
                const double near = e.logNear + e.logUnrelated;
                const double far = e.logFar + e.logUnrelated;
                sum += std::isfinite(far)
                           ? std::max(near, far) + std::log1p(std::exp(-std::abs(near - far)))
                           : near;
            }
            terms.push_back(sum);
            maxLog = std::max(maxLog, sum);
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
    const double logNull = buildingNull({{first, &model}});
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
