// Magnetic loop closers judged as place recognition is (precision and recall against the
// truth), side by side on every recording (bench/magnetic_recordings.h):
//   bench_magnetic_recall DATA_DIR OUT_DIR SEEDS INI [INI ...] [--only NAME]
// Each recording is imported with the drift model for seeds 1..SEEDS and run through
// lodestone-slam's code path with each INI (a config_ini/ name, or a path); its closures.csv is
// judged by lodestone-eval closures' rules (eval::evaluateClosures: 2 m revisit passes, a pass
// found when a closure placing its later node within 0.5 m of the truth ends in it), passes
// counted apart by direction. A row per recording and INI: passes found over all seeds (at any
// score), the worst seed's recall, wrong closures (> 0.5 m), ATE median / worst, real-time
// factor.
#include "magnetic_recordings.h"

#include <lodestone/eval/ClosureEval.h>
#include <lodestone/io/MagneticRecordingImport.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/obs/registerAllClasses.h>
#include <lodestone/slamapp/SlamRun.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>

using namespace lodestone;

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? NAN : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

std::string fraction(std::size_t found, std::size_t all) {
    char b[64];
    if (all == 0) return "-";
    std::snprintf(b, sizeof b, "%zu / %zu (%.2f)", found, all, double(found) / double(all));
    return b;
}

struct Row {
    std::size_t passes[2]{0, 0}, found[2]{0, 0}, wrong{0}, closures{0};
    double worstRecall{INFINITY};
    std::vector<double> ate, realtime;
};

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> inis;
    std::string only;
    for (int i = 4; i < argc; ++i) {
        if (std::string(argv[i]) == "--only" && i + 1 < argc) {
            only = argv[++i];
        } else {
            inis.push_back(argv[i]);
        }
    }
    if (argc < 5 || inis.empty()) {
        std::cerr << "usage: bench_magnetic_recall DATA_DIR OUT_DIR SEEDS INI [INI ...] [--only NAME]\n";
        return 2;
    }
    const std::string data = argv[1], out = argv[2];
    const int seeds = std::atoi(argv[3]);
    registerAllClasses();
    const std::string cfg = LODESTONE_CONFIG_INI_DIR;
    std::printf("| recording | INI | same-direction passes found | opposite-direction found | "
                "worst seed's recall | closures | wrong (> 0.5 m) | ATE median / worst [m] | "
                "real-time factor |\n|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& rec : benchRecordings(data)) {
        if (!only.empty() && rec.name.find(only) == std::string::npos) continue;
        const auto recording = rec.read();
        for (const auto& ini : inis) {
            Row row;
            for (int seed = 1; seed <= seeds; ++seed) {
                std::string stem = rec.name + "_s" + std::to_string(seed);
                std::replace(stem.begin(), stem.end(), ' ', '_');
                io::OdometryDriftModel model;
                model.seed = static_cast<std::uint64_t>(seed);
                const auto imported =
                    io::writeMagneticRecording(recording, out + "/" + stem + ".rawlog", model);
                slamapp::SlamRunOptions o;
                o.rawlog = imported.rawlog;
                o.groundTruth = imported.groundTruth;
                o.config = ini.find('/') != std::string::npos ? ini : cfg + "/" + ini;
                o.outDir = out + "/" + stem + "_run";
                o.quiet = true;
                std::ostringstream sout, serr;
                const auto t0 = std::chrono::steady_clock::now();
                const auto r = slamapp::runSlam(o, sout, serr);
                const double wall =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                if (r.exitCode != 0 || !r.ateRmse) {
                    std::cerr << rec.name << " " << ini << ": " << serr.str();
                    return 1;
                }
                row.ate.push_back(*r.ateRmse);
                row.realtime.push_back(imported.duration / wall);
                const auto truth = io::readTumTrajectory(imported.groundTruth);
                const auto nodes = io::readTumTrajectory(o.outDir + "/trajectory.tum");
                const auto closures = eval::readClosureLog(o.outDir + "/closures.csv");
                std::size_t passes = 0, found = 0;
                const auto qs = eval::evaluateClosures(closures, nodes, truth);
                // Passes are the run's (every matcher sees the same); a pass is found by any.
                std::size_t byDir[2] = {0, 0};
                if (qs.empty()) {
                    // no closure at all: count the passes with an empty matcher's evaluation
                    eval::ReportedClosure none;
                    none.source = "none";
                    none.fromTime = none.toTime = -1e9;
                    const auto q = eval::evaluateClosures({none}, nodes, truth);
                    for (int d = 0; d < 2; ++d) row.passes[d] += q[0].byDirection[d].passes;
                    passes = q[0].passes;
                } else {
                    for (int d = 0; d < 2; ++d) row.passes[d] += qs[0].byDirection[d].passes;
                    passes = qs[0].passes;
                    for (const auto& q : qs) {
                        row.closures += q.proposals;
                        row.wrong += q.wrong;
                        for (int d = 0; d < 2; ++d) byDir[d] = std::max(byDir[d], q.byDirection[d].detected);
                    }
                }
                for (int d = 0; d < 2; ++d) {
                    row.found[d] += byDir[d];
                    found += byDir[d];
                }
                if (passes) row.worstRecall = std::min(row.worstRecall, double(found) / double(passes));
            }
            std::printf("| %s | %s | %s | %s | %.2f | %zu | %zu | %.3f / %.3f | %.0fx |\n",
                        rec.name.c_str(), ini.c_str(), fraction(row.found[0], row.passes[0]).c_str(),
                        fraction(row.found[1], row.passes[1]).c_str(),
                        std::isfinite(row.worstRecall) ? row.worstRecall : NAN, row.closures, row.wrong,
                        median(row.ate), *std::max_element(row.ate.begin(), row.ate.end()),
                        median(row.realtime));
            std::fflush(stdout);
        }
    }
    return 0;
}
