#include <lodestone/eval/ClosureFunnel.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace lodestone::eval {

std::vector<ClosureFunnel> readClosureFunnels(const std::string& reportPath,
                                              const std::vector<RevisitPass>& passes,
                                              const std::vector<MatcherQuality>& qualities) {
    std::ifstream in(reportPath);
    if (!in) throw std::runtime_error(reportPath + ": cannot open report");
    nlohmann::json report;
    try {
        report = nlohmann::json::parse(in);
    } catch (const std::exception& e) {
        throw std::runtime_error(reportPath + ": not a lodestone-slam report.json: " + e.what());
    }
    std::vector<ClosureFunnel> out;
    const auto erd = report.value("engine", nlohmann::json::object())
                         .value("edge_decider", nlohmann::json::object());
    for (const auto& child : erd.value("children", nlohmann::json::array({erd}))) {
        if (!child.is_object() || !child.contains("truth_funnel")) continue;
        const auto& f = child["truth_funnel"];
        ClosureFunnel funnel;
        funnel.decider = child.value("class", "");
        const auto names = f.value("stage_names", nlohmann::json::object());
        for (const auto& [k, name] : names.items()) {
            const auto at = std::stoul(k);
            if (funnel.stageNames.size() <= at) funnel.stageNames.resize(at + 1);
            funnel.stageNames[at] = name.get<std::string>();
        }
        const auto truthInside = f.value("truth_inside_gate", nlohmann::json());
        funnel.truthInsideGate = truthInside.is_number() ? truthInside.get<double>() : NAN;
        std::vector<bool> found(passes.size(), false);
        for (const auto& q : qualities) {
            if (q.source != funnel.decider) continue;
            for (const auto p : q.detectedPasses) found.at(p) = true;
        }
        const auto nodes = f.value("query_node", nlohmann::json::array());
        const auto stages = f.value("stage", nlohmann::json::array());
        for (std::size_t p = 0; p < passes.size(); ++p) {
            ++funnel.passes;
            if (found[p]) continue;
            ++funnel.missed;
            int furthest = -1;
            for (std::size_t i = 0; i < std::min(nodes.size(), stages.size()); ++i) {
                const double node = nodes[i].get<double>();
                if (node >= double(passes[p].first) && node <= double(passes[p].last))
                    furthest = std::max(furthest, stages[i].get<int>());
            }
            ++funnel.missedBy[static_cast<int>(passes[p].direction)][furthest];
        }
        out.push_back(std::move(funnel));
    }
    return out;
}

std::string missedByStage(const ClosureFunnel& f) {
    std::string cells;
    for (int stage = -1; stage < int(f.stageNames.size()); ++stage) {
        std::size_t count[2] = {0, 0};
        for (int d = 0; d < 2; ++d) {
            const auto it = f.missedBy[d].find(stage);
            if (it != f.missedBy[d].end()) count[d] = it->second;
        }
        if (count[0] + count[1] == 0) continue;
        cells += (cells.empty() ? "" : ", ") +
                 (stage < 0 ? std::string("no query") : f.stageNames[std::size_t(stage)]) + " " +
                 std::to_string(count[0]) + " / " + std::to_string(count[1]);
    }
    return cells.empty() ? "none" : cells;
}

std::string formatClosureFunnels(const std::vector<ClosureFunnel>& funnels) {
    std::string out =
        "| matcher | passes missed / all | missed, by the furthest stage their true place reached "
        "(same / opposite direction) | truth inside the gate |\n|---|---|---|---|\n";
    char line[64];
    for (const auto& f : funnels) {
        std::snprintf(line, sizeof line, "%.3f", f.truthInsideGate);
        out += "| " + f.decider + " | " + std::to_string(f.missed) + " / " +
               std::to_string(f.passes) + " | " + missedByStage(f) + " | " +
               (std::isnan(f.truthInsideGate) ? std::string("-") : std::string(line)) + " |\n";
    }
    return out;
}

}  // namespace lodestone::eval
