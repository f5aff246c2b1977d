#include <lodestone/eval/ClosureEval.h>
#include <lodestone/eval/TrajectoryError.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <set>
#include <stdexcept>

namespace lodestone::eval {

/** Runs of consecutive revisit nodes of one direction, cut into pieces. */
std::vector<RevisitPass> revisitPasses(const std::vector<io::TumPose>& trajectory,
                                       const std::vector<io::TumPose>& truth,
                                       const ClosureEvalOptions& o) {
    std::vector<const io::TumPose*> gt(trajectory.size());
    std::vector<double> travel(trajectory.size(), 0);
    const io::TumPose* last = nullptr;
    double s = 0;
    for (std::size_t i = 0; i < trajectory.size(); ++i) {
        gt[i] = truthAt(truth, trajectory[i].timestamp, o.maxDt);
        if (gt[i] && last) s += gt[i]->pose.distanceTo(last->pose);
        if (gt[i]) last = gt[i];
        travel[i] = s;
    }
    enum Kind { None, Same, Opposite };
    std::vector<Kind> kind(trajectory.size(), None);
    for (std::size_t i = 0; i < trajectory.size(); ++i) {
        if (!gt[i]) continue;
        for (std::size_t j = 0; j < i && travel[i] - travel[j] >= o.minGap; ++j) {
            if (!gt[j] || gt[i]->pose.distanceTo(gt[j]->pose) > o.radius) continue;
            const double dyaw =
                std::abs(std::remainder(gt[i]->pose.yaw() - gt[j]->pose.yaw(), 2 * M_PI));
            if (dyaw <= o.revisitYaw) {
                kind[i] = Same;  // (a same-way visit decides: see PassDirection)
                break;
            }
            if (dyaw >= M_PI - o.revisitYaw) kind[i] = Opposite;
        }
    }
    std::vector<RevisitPass> passes;
    for (std::size_t i = 0; i < kind.size();) {
        if (kind[i] == None) {
            ++i;
            continue;
        }
        std::size_t j = i;
        while (j + 1 < kind.size() && kind[j + 1] == kind[i]) ++j;
        const auto direction = kind[i] == Same ? PassDirection::Same : PassDirection::Opposite;
        // A long revisit (a whole lap driven again) is many places to recognise: cut it into
        // pieces of `pieceLength`, the last one joined to its predecessor when short.
        if (travel[j] - travel[i] >= o.minPassLength) {
            std::size_t start = i;
            for (std::size_t k = i; k <= j; ++k) {
                if (travel[k] - travel[start] >= o.pieceLength &&
                    travel[j] - travel[k] >= o.minPassLength) {
                    passes.push_back({start, k - 1, direction});
                    start = k;
                }
            }
            passes.push_back({start, j, direction});
        }
        i = j + 1;
    }
    return passes;
}

double closureErrorChi2(const ReportedClosure& c, const mrpt::poses::CPose3D& trueFrom,
                        const mrpt::poses::CPose3D& trueTo) {
    const Eigen::Matrix2d C = c.translationCovariance.topLeftCorner<2, 2>();
    const Eigen::LLT<Eigen::Matrix2d> llt(C);
    if (!C.allFinite() || llt.info() != Eigen::Success) return NAN;
    const mrpt::poses::CPose3D truth = trueTo - trueFrom;  // `to` in the frame of `from`
    const Eigen::Vector2d e(c.measured.x() - truth.x(), c.measured.y() - truth.y());
    return e.dot(llt.solve(e));
}

std::vector<MatcherQuality> evaluateClosures(const std::vector<ReportedClosure>& closures,
                                             const std::vector<io::TumPose>& trajectory,
                                             const std::vector<io::TumPose>& truth,
                                             const ClosureEvalOptions& o) {
    const auto passes = revisitPasses(trajectory, truth, o);
    const auto passOf = [&](long long node) -> std::ptrdiff_t {
        const auto it =
            std::upper_bound(passes.begin(), passes.end(), static_cast<std::size_t>(node),
                             [](std::size_t v, const RevisitPass& p) { return v < p.first; });
        if (it == passes.begin()) return -1;
        const auto& p = *(it - 1);
        return static_cast<std::size_t>(node) <= p.last ? (it - 1) - passes.begin() : -1;
    };
    struct Judged {
        const ReportedClosure* closure;
        double error, chi2;
    };
    std::map<std::string, std::vector<Judged>> bySource;
    for (const auto& c : closures) {
        const io::TumPose* a = truthAt(truth, c.fromTime, o.maxDt);
        const io::TumPose* b = truthAt(truth, c.toTime, o.maxDt);
        const double error = a && b ? (a->pose + c.measured).distanceTo(b->pose) : NAN;
        const double chi2 = a && b ? closureErrorChi2(c, a->pose, b->pose) : NAN;
        bySource[c.source].push_back({&c, error, chi2});
    }
    std::vector<MatcherQuality> out;
    for (const auto& [source, list] : bySource) {
        MatcherQuality q;
        q.source = source;
        q.passes = passes.size();
        std::vector<double> errors;
        double worstWrong = -INFINITY;
        for (const auto& [c, error, chi2] : list) {
            ++q.proposals;
            q.kept += c->kept;
            q.hypotheses += c->hypothesis;
            if (std::isnan(error)) continue;
            ++q.judged;
            errors.push_back(error);
            const bool right = error <= o.radius;
            q.right += right;
            q.wrong += !right;
            q.keptWrong += c->kept && !right;
            q.hypothesesWrong += c->hypothesis && !right;
            if (!right) worstWrong = std::max(worstWrong, c->score);
            if (std::isnan(chi2)) continue;
            ++q.covarianceJudged;
            q.insideOwnRegion += chi2 <= o.ownRegionChi2;
            q.wrongInsideOwnRegion += !right && chi2 <= o.ownRegionChi2;
        }
        if (!errors.empty()) {
            std::sort(errors.begin(), errors.end());
            q.medianError = errors[errors.size() / 2];
            q.maxError = errors.back();
        }
        if (q.wrong) q.threshold = worstWrong;
        std::set<std::ptrdiff_t> any, clean;
        for (const auto& [c, error, chi2] : list) {
            if (!(error <= o.radius)) continue;
            const auto p = passOf(c->toNode);
            if (p < 0) continue;
            any.insert(p);
            if (c->score > worstWrong) clean.insert(p);
        }
        q.passesDetected = any.size();
        q.detectedPasses.assign(any.begin(), any.end());
        q.passesAt100 = clean.size();
        for (const auto& p : passes) ++q.byDirection[static_cast<int>(p.direction)].passes;
        for (const auto p : any) ++q.byDirection[static_cast<int>(passes[p].direction)].detected;
        for (const auto p : clean) ++q.byDirection[static_cast<int>(passes[p].direction)].at100;
        out.push_back(q);
    }
    return out;
}

std::string formatClosureQuality(const std::vector<MatcherQuality>& qs,
                                 const ClosureEvalOptions& o) {
    std::string out =
        "| matcher | proposed | right | wrong | precision | error median / max m | kept (wrong) | "
        "hypotheses (wrong) | passes | recall | recall at 100 % precision | same direction: "
        "passes, "
        "recall at 100 % | opposite direction: passes, recall at 100 % | score threshold | "
        "inside their own 99.73 % (wrong ones) |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    char line[768];
    for (const auto& q : qs) {
        char threshold[32] = "none wrong";
        if (!std::isnan(q.threshold))
            std::snprintf(threshold, sizeof threshold, "> %.4g", q.threshold);
        char consistency[64] = "-";
        if (q.covarianceJudged) {
            std::snprintf(consistency, sizeof consistency, "%.3f (%zu of %zu)", q.consistency(),
                          q.wrongInsideOwnRegion, q.wrong);
        }
        std::snprintf(line, sizeof line,
                      "| %s | %zu | %zu | %zu | %.3f | %.3f / %.3f | %zu (%zu) | %zu (%zu) | %zu | "
                      "%.3f | %.3f | %zu, %.3f | %zu, %.3f | %s | %s |\n",
                      q.source.c_str(), q.proposals, q.right, q.wrong, q.precision(), q.medianError,
                      q.maxError, q.kept, q.keptWrong, q.hypotheses, q.hypothesesWrong, q.passes,
                      q.recall(), q.recallAt100(), q.byDirection[0].passes,
                      q.byDirection[0].recallAt100(), q.byDirection[1].passes,
                      q.byDirection[1].recallAt100(), threshold, consistency);
        out += line;
    }
    std::snprintf(line, sizeof line,
                  "\nright: the measured pose lands within %.2f m of the truth; a pass: %.1f m "
                  "(or less, down to %.1f m) of revisit, nodes within %.2f m of a place passed "
                  "%.1f m of travel before, facing within %.0f deg of the same way (or of the "
                  "opposite way: opposite direction); recall: passes with a right closure "
                  "ending in them, at 100 %% precision: scoring above every wrong one; inside "
                  "their own 99.73 %%: the share of closures whose horizontal error's squared "
                  "Mahalanobis distance under their claimed covariance is within %.2f\n",
                  o.radius, o.pieceLength, o.minPassLength, o.radius, o.minGap,
                  o.revisitYaw * 180 / M_PI, o.ownRegionChi2);
    out += line;
    return out;
}

}  // namespace lodestone::eval
