#include <lodestone/eval/ClosureEval.h>
#include <lodestone/eval/TrajectoryError.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

namespace lodestone::eval {

namespace {

std::vector<std::string> splitCsv(const std::string& line) {
    std::vector<std::string> out;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) out.push_back(cell);
    return out;
}

double number(const std::string& cell, const std::string& where) {
    std::size_t used = 0;
    double v = 0;
    try {
        v = std::stod(cell, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != cell.size() || cell.empty() || !std::isfinite(v))
        throw std::runtime_error(where + ": '" + cell + "' is not a finite number");
    return v;
}

/** Revisit passes over the run's nodes: runs of consecutive revisit nodes, as node-ID ranges. */
std::vector<std::pair<std::size_t, std::size_t>> revisitPasses(
    const std::vector<io::TumPose>& trajectory, const std::vector<io::TumPose>& truth,
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
    std::vector<bool> revisit(trajectory.size(), false);
    for (std::size_t i = 0; i < trajectory.size(); ++i) {
        if (!gt[i]) continue;
        for (std::size_t j = 0; j < i && travel[i] - travel[j] >= o.minGap; ++j) {
            if (!gt[j]) continue;
            const double d = gt[i]->pose.distanceTo(gt[j]->pose);
            const double dyaw =
                std::abs(std::remainder(gt[i]->pose.yaw() - gt[j]->pose.yaw(), 2 * M_PI));
            if (d <= o.radius && dyaw <= o.revisitYaw) {
                revisit[i] = true;
                break;
            }
        }
    }
    std::vector<std::pair<std::size_t, std::size_t>> passes;
    for (std::size_t i = 0; i < revisit.size();) {
        if (!revisit[i]) {
            ++i;
            continue;
        }
        std::size_t j = i;
        while (j + 1 < revisit.size() && revisit[j + 1]) ++j;
        // A long revisit (a whole lap driven again) is many places to recognise: cut it into
        // pieces of `pieceLength`, the last one joined to its predecessor when short.
        if (travel[j] - travel[i] >= o.minPassLength) {
            std::size_t start = i;
            for (std::size_t k = i; k <= j; ++k) {
                if (travel[k] - travel[start] >= o.pieceLength &&
                    travel[j] - travel[k] >= o.minPassLength) {
                    passes.emplace_back(start, k - 1);
                    start = k;
                }
            }
            passes.emplace_back(start, j);
        }
        i = j + 1;
    }
    return passes;
}

}  // namespace

std::vector<ReportedClosure> readClosureLog(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open closure log");
    std::string line;
    if (!std::getline(in, line) || line.rfind("from_node,to_node,", 0) != 0)
        throw std::runtime_error(path + ": line 1: not a lodestone-slam closures.csv header");
    std::vector<ReportedClosure> out;
    for (int n = 2; std::getline(in, line); ++n) {
        if (line.empty()) continue;
        const std::string where = path + ": line " + std::to_string(n);
        const auto c = splitCsv(line);
        if (c.size() != 16) {
            throw std::runtime_error(where + ": " + std::to_string(c.size()) +
                                     " fields, expected 16");
        }
        ReportedClosure r;
        r.fromNode = static_cast<long long>(number(c[0], where));
        r.toNode = static_cast<long long>(number(c[1], where));
        r.fromTime = number(c[2], where);
        r.toTime = number(c[3], where);
        r.source = c[4];
        r.score = number(c[6], where);
        r.hypothesis = number(c[8], where) != 0;
        r.kept = number(c[9], where) != 0;
        r.measured =
            mrpt::poses::CPose3D(number(c[10], where), number(c[11], where), number(c[12], where),
                                 number(c[13], where), number(c[14], where), number(c[15], where));
        out.push_back(r);
    }
    return out;
}

std::vector<MatcherQuality> evaluateClosures(const std::vector<ReportedClosure>& closures,
                                             const std::vector<io::TumPose>& trajectory,
                                             const std::vector<io::TumPose>& truth,
                                             const ClosureEvalOptions& o) {
    const auto passes = revisitPasses(trajectory, truth, o);
    const auto passOf = [&](long long node) -> std::ptrdiff_t {
        const auto it =
            std::upper_bound(passes.begin(), passes.end(), static_cast<std::size_t>(node),
                             [](std::size_t v, const std::pair<std::size_t, std::size_t>& p) {
                                 return v < p.first;
                             });
        if (it == passes.begin()) return -1;
        const auto& p = *(it - 1);
        return static_cast<std::size_t>(node) <= p.second ? (it - 1) - passes.begin() : -1;
    };
    std::map<std::string, std::vector<std::pair<const ReportedClosure*, double>>> bySource;
    for (const auto& c : closures) {
        const io::TumPose* a = truthAt(truth, c.fromTime, o.maxDt);
        const io::TumPose* b = truthAt(truth, c.toTime, o.maxDt);
        const double error = a && b ? (a->pose + c.measured).distanceTo(b->pose) : NAN;
        bySource[c.source].emplace_back(&c, error);
    }
    std::vector<MatcherQuality> out;
    for (const auto& [source, list] : bySource) {
        MatcherQuality q;
        q.source = source;
        q.passes = passes.size();
        std::vector<double> errors;
        double worstWrong = -INFINITY;
        for (const auto& [c, error] : list) {
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
        }
        if (!errors.empty()) {
            std::sort(errors.begin(), errors.end());
            q.medianError = errors[errors.size() / 2];
            q.maxError = errors.back();
        }
        if (q.wrong) q.threshold = worstWrong;
        std::set<std::ptrdiff_t> any, clean;
        for (const auto& [c, error] : list) {
            if (!(error <= o.radius)) continue;
            const auto p = passOf(c->toNode);
            if (p < 0) continue;
            any.insert(p);
            if (c->score > worstWrong) clean.insert(p);
        }
        q.passesDetected = any.size();
        q.passesAt100 = clean.size();
        out.push_back(q);
    }
    return out;
}

std::string formatClosureQuality(const std::vector<MatcherQuality>& qs,
                                 const ClosureEvalOptions& o) {
    std::string out =
        "| matcher | proposed | right | wrong | precision | error median / max m | kept (wrong) | "
        "hypotheses (wrong) | passes | recall | recall at 100 % precision | score threshold |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    char line[512];
    for (const auto& q : qs) {
        char threshold[32] = "none wrong";
        if (!std::isnan(q.threshold))
            std::snprintf(threshold, sizeof threshold, "> %.4g", q.threshold);
        std::snprintf(line, sizeof line,
                      "| %s | %zu | %zu | %zu | %.3f | %.3f / %.3f | %zu (%zu) | %zu (%zu) | %zu | "
                      "%.3f | %.3f | %s |\n",
                      q.source.c_str(), q.proposals, q.right, q.wrong, q.precision(), q.medianError,
                      q.maxError, q.kept, q.keptWrong, q.hypotheses, q.hypothesesWrong, q.passes,
                      q.recall(), q.recallAt100(), threshold);
        out += line;
    }
    std::snprintf(line, sizeof line,
                  "\nright: the measured pose lands within %.2f m of the truth; a pass: %.1f m "
                  "(or less, down to %.1f m) of revisit, nodes within %.2f m and %.0f deg of a "
                  "place passed %.1f m of travel before; recall: passes with a right closure "
                  "ending in them, at 100 %% precision: scoring above every wrong one\n",
                  o.radius, o.pieceLength, o.minPassLength, o.radius, o.revisitYaw * 180 / M_PI,
                  o.minGap);
    out += line;
    return out;
}

}  // namespace lodestone::eval
