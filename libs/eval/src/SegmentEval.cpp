#include <lodestone/eval/SegmentEval.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <stdexcept>

namespace lodestone::eval {

SegmentEvaluation evaluateSegments(const std::vector<outputs::NodeRow>& nodes,
                                   const std::vector<io::TumPose>& trajectory,
                                   const std::vector<io::TumPose>& truth, double maxDt) {
    SegmentEvaluation e;
    e.whole = absoluteTrajectoryError(trajectory, truth, maxDt);
    // Each pose's segment: the node of the same timestamp (both written from one graph).
    std::vector<std::pair<double, int>> segmentAt;
    segmentAt.reserve(nodes.size());
    for (const auto& n : nodes) segmentAt.emplace_back(n.timestamp, n.segment);
    std::sort(segmentAt.begin(), segmentAt.end());
    std::map<int, std::vector<io::TumPose>> pieces;
    for (const auto& p : trajectory) {
        const auto it = std::lower_bound(segmentAt.begin(), segmentAt.end(),
                                         std::make_pair(p.timestamp - 1e-6, -1));
        if (it == segmentAt.end() || std::abs(it->first - p.timestamp) > 1e-6) continue;
        pieces[it->second].push_back(p);
    }
    double sum = 0;
    for (const auto& [segment, poses] : pieces) {
        if (poses.size() < 3) continue;
        SegmentError s;
        s.segment = segment;
        s.ate = absoluteTrajectoryError(poses, truth, maxDt);
        if (s.ate.pairs < 3) continue;
        sum += s.ate.rmse * s.ate.rmse * static_cast<double>(s.ate.pairs);
        e.pooledPairs += s.ate.pairs;
        e.segments.push_back(std::move(s));
    }
    if (e.pooledPairs > 0) e.pooledRmse = std::sqrt(sum / static_cast<double>(e.pooledPairs));
    return e;
}

bool readVoGaps(const std::string& reportJson, std::vector<double>& gapSeconds) {
    std::ifstream in(reportJson);
    if (!in) throw std::runtime_error(reportJson + ": cannot open report");
    nlohmann::json j;
    try {
        in >> j;
    } catch (const std::exception& ex) {
        throw std::runtime_error(reportJson + ": not JSON (" + ex.what() + ")");
    }
    const auto decider = j.find("engine");
    if (decider == j.end() || !decider->contains("node_decider")) return false;
    const auto& stats = (*decider)["node_decider"].value("stats", nlohmann::json::object());
    const auto gaps = stats.find("vo_gap_seconds");
    if (gaps == stats.end() || !gaps->is_array()) return false;
    gapSeconds.clear();
    for (const auto& g : *gaps) {
        if (!g.is_number()) throw std::runtime_error(reportJson + ": vo_gap_seconds holds a non-number");
        gapSeconds.push_back(g.get<double>());
    }
    return true;
}

std::string formatSegmentEvaluation(const SegmentEvaluation& e) {
    std::string out;
    char line[200];
    std::snprintf(line, sizeof(line), "whole run     ATE RMSE %.4f m over %zu poses\n", e.whole.rmse,
                  e.whole.pairs);
    out += line;
    if (e.gapsReported) {
        double total = 0, longest = 0;
        for (const double g : e.gapSeconds) {
            total += g;
            longest = std::max(longest, g);
        }
        std::snprintf(line, sizeof(line), "VO gaps       %zu, %.1f s in all, the longest %.1f s\n",
                      e.gapSeconds.size(), total, longest);
        out += line;
    }
    std::snprintf(line, sizeof(line),
                  "segments      %zu, each aligned on its own: ATE RMSE %.4f m pooled over %zu poses\n",
                  e.segments.size(), e.pooledRmse, e.pooledPairs);
    out += line;
    for (const auto& s : e.segments) {
        std::snprintf(line, sizeof(line), "  segment %-3d %5zu poses   ATE RMSE %.4f m   max %.4f\n",
                      s.segment, s.ate.pairs, s.ate.rmse, s.ate.max);
        out += line;
    }
    return out;
}

}  // namespace lodestone::eval
