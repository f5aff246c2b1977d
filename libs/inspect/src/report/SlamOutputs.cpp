#include <lodestone/inspect/report/ReportHtml.h>
#include <lodestone/inspect/report/SlamOutputs.h>
#include <lodestone/outputs/RunFiles.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace lodestone::inspect::report {

namespace fs = std::filesystem;
using outputs::RunFile;

namespace {
// The handful of report.json figures a reader of the report wants first.
void readFacts(const std::string& path, SlamOutputs& out) {
    std::ifstream in(path);
    nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded() || !j.is_object()) {
        out.missing.push_back(path + ": not JSON");
        return;
    }
    const auto get = [&](std::initializer_list<const char*> keys) -> const nlohmann::json* {
        const nlohmann::json* at = &j;
        for (const char* k : keys) {
            if (!at->is_object() || !at->contains(k)) return nullptr;
            at = &(*at)[k];
        }
        return at;
    };
    if (const auto* c = get({"engine", "counts"})) {
        for (const char* k : {"nodes", "keyframes", "loop_closures", "loop_closures_rejected",
                              "rgbd_frames", "relocations"}) {
            if (c->contains(k) && (*c)[k].is_number()) out.facts.push_back({k, (*c)[k].dump()});
        }
    }
    if (const auto* r = get({"timing", "real_time_factor"}); r && r->is_number()) {
        out.facts.push_back({"real-time factor", fixedText(r->get<double>(), 2) + "x"});
    }
    if (const auto* a = get({"ate", "rmse_m"}); a && a->is_number()) {
        out.facts.push_back({"ATE RMSE (lodestone-slam)", fixedText(a->get<double>(), 4) + " m"});
    }
    if (const auto* e = get({"error"}); e && e->is_string()) {
        out.facts.push_back({"run stopped by", e->get<std::string>()});
    }
}
}  // namespace

SlamOutputs readSlamOutputs(const std::string& dir, const std::string& groundTruth) {
    SlamOutputs out;
    out.dir = dir;
    if (!fs::is_directory(dir)) throw std::runtime_error(dir + ": not a lodestone-slam output folder");
    out.trajectory = io::readTumTrajectory(outputs::pathIn(dir, RunFile::Trajectory));
    const auto optional = [&](RunFile file, const auto& read) {
        const fs::path p = outputs::pathIn(dir, file);
        if (!fs::exists(p)) {
            out.missing.push_back(p.string() + ": absent");
            return;
        }
        try {
            read(p.string());
        } catch (const std::exception& e) {
            out.missing.push_back(e.what());
        }
    };
    optional(RunFile::Closures, [&](const std::string& p) { out.closures = outputs::readClosureTable(p); });
    optional(RunFile::Nodes, [&](const std::string& p) { out.nodes = outputs::readNodeTable(p); });
    optional(RunFile::Report, [&](const std::string& p) {
        readFacts(p, out);
        out.kidnaps = eval::readReportedKidnaps(p);
    });
    if (!groundTruth.empty()) {
        out.groundTruth = io::readTumTrajectory(groundTruth);
        out.groundTruthPath = groundTruth;
    } else if (fs::exists(outputs::pathIn(dir, RunFile::GroundTruth))) {
        out.groundTruthPath = outputs::pathIn(dir, RunFile::GroundTruth);
        out.groundTruth = io::readTumTrajectory(out.groundTruthPath);
    }
    return out;
}

}  // namespace lodestone::inspect::report
