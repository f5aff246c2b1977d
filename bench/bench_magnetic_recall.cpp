// Magnetic loop closers judged as place recognition (precision and recall against the truth),
// side by side on every recording (bench/magnetic_recordings.h):
//   bench_magnetic_recall DATA_DIR OUT_DIR SEEDS INI [INI ...] [--only NAME] [--drift-scale F]
//                         [--variant SPEC]
// Each recording is imported with the drift model for seeds 1..SEEDS and run through
// lodestone-slam's code path (the rawlog written to disk and read back) with each INI (a
// config_ini/ name, or a path); its closures.csv is judged by lodestone-eval closures' rules
// (eval::evaluateClosures: 2 m revisit passes, a pass found when a closure placing its later node
// within 0.5 m of the truth ends in it), passes counted apart by direction. Table 1, a row per
// recording and INI: passes found over all seeds, the worst seed's recall each way, precision,
// wrong closures (> 0.5 m), the share of closures whose error lies inside their own claimed
// 99.73 % region (and how many of the wrong ones do), ATE median / worst, real-time factor.
// Table 2, a row per closer with a truth funnel (both magnetic ones): every pass it missed, by
// the furthest stage its true place reached in any query inside it; how often the truth lay
// inside its position gate.
// --drift-scale F scales the drift model's heading bias and noise (0: odometry without error,
// so what is left of the ATE is what the closures themselves do to the reference trajectory).
// --variant SPEC runs each recording made harder (datasets/MagneticRecordingVariants.h: quiet:A, gauss,
// normalized:F, rate:HZ, noise:S), its draws seeded by the run's seed.
#include <lodestone/datasets/MagneticRecordingImport.h>
#include <lodestone/datasets/MagneticRecordingVariants.h>
#include <lodestone/eval/ClosureEval.h>
#include <lodestone/eval/ClosureFunnel.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/obs/registerAllClasses.h>
#include <lodestone/outputs/ClosureTable.h>
#include <lodestone/outputs/RunFiles.h>
#include <lodestone/slamapp/SlamRun.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>

#include "magnetic_recordings.h"

using namespace lodestone;

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty()      ? NAN
           : v.size() % 2 ? v[v.size() / 2]
                          : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

std::string fraction(std::size_t found, std::size_t all) {
    char b[64];
    if (all == 0) return "-";
    std::snprintf(b, sizeof b, "%zu / %zu (%.2f)", found, all, double(found) / double(all));
    return b;
}

struct Row {
    std::size_t passes[2]{0, 0}, found[2]{0, 0}, right{0}, judged{0}, wrong{0}, closures{0};
    /** Closures judged by their own claimed covariance, inside its 99.73 % region, and of the
     * wrong ones those inside it. */
    std::size_t covarianceJudged{0}, insideOwnRegion{0}, wrongInsideOwnRegion{0};
    double worst[2]{INFINITY, INFINITY};  // the worst seed's recall, each direction
    std::vector<double> ate, realtime;
    /** Each closer's funnel over all seeds: the passes it missed by furthest stage, and per
     * seed the share of true places inside its gate (a closer beside another may miss a pass
     * the other found). */
    struct Funnel {
        eval::ClosureFunnel missed;
        std::vector<double> insideGate;
    };
    std::map<std::string, Funnel> funnels;  // by decider
};

/** One seed's run judged into `row` (passes and right closures within `radius`); false (with
 * the message on stderr) if it failed. */
bool judgeRun(const slamapp::SlamRunOptions& o, Row& row, double radius) {
    const auto truth = io::readTumTrajectory(o.groundTruth);
    const auto nodes = io::readTumTrajectory(o.outDir + "/trajectory.tum");
    eval::ClosureEvalOptions judge;
    judge.radius = radius;
    const auto passes = eval::revisitPasses(nodes, truth, judge);
    const auto qs = eval::evaluateClosures(
        outputs::readClosureTable(outputs::pathIn(o.outDir, outputs::RunFile::Closures)), nodes,
        truth, judge);
    std::vector<bool> found(passes.size(), false);
    for (const auto& q : qs) {
        row.closures += q.proposals;
        row.wrong += q.wrong;
        row.right += q.right;
        row.judged += q.judged;
        row.covarianceJudged += q.covarianceJudged;
        row.insideOwnRegion += q.insideOwnRegion;
        row.wrongInsideOwnRegion += q.wrongInsideOwnRegion;
        for (const auto p : q.detectedPasses) found[p] = true;  // by any matcher
    }
    std::size_t all[2] = {0, 0}, hit[2] = {0, 0};
    for (std::size_t p = 0; p < passes.size(); ++p) {
        const int d = static_cast<int>(passes[p].direction);
        ++all[d];
        hit[d] += found[p];
    }
    for (const auto& f : eval::readClosureFunnels(o.outDir + "/report.json", passes, qs)) {
        auto& mine = row.funnels[f.decider];
        mine.missed.stageNames = f.stageNames;
        mine.insideGate.push_back(f.truthInsideGate);
        for (int d = 0; d < 2; ++d)
            for (const auto& [stage, count] : f.missedBy[d])
                mine.missed.missedBy[d][stage] += count;
    }
    for (int d = 0; d < 2; ++d) {
        row.passes[d] += all[d];
        row.found[d] += hit[d];
        if (all[d]) row.worst[d] = std::min(row.worst[d], double(hit[d]) / double(all[d]));
    }
    return true;
}

std::string worstOf(double v) {
    char b[16];
    if (!std::isfinite(v)) return "-";
    std::snprintf(b, sizeof b, "%.2f", v);
    return b;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> inis;
    std::string only, variant;
    double driftScale = 1.0, radius = 0.5;
    for (int i = 4; i < argc; ++i) {
        if (std::string(argv[i]) == "--only" && i + 1 < argc) {
            only = argv[++i];
        } else if (std::string(argv[i]) == "--judge-radius" && i + 1 < argc) {
            radius = std::atof(argv[++i]);
        } else if (std::string(argv[i]) == "--variant" && i + 1 < argc) {
            variant = argv[++i];
        } else if (std::string(argv[i]) == "--drift-scale" && i + 1 < argc) {
            driftScale = std::atof(argv[++i]);
        } else {
            inis.push_back(argv[i]);
        }
    }
    if (argc < 5 || inis.empty()) {
        std::cerr
            << "usage: bench_magnetic_recall DATA_DIR OUT_DIR SEEDS INI [INI ...] [--only NAME] "
               "[--drift-scale F] [--variant SPEC] [--judge-radius M]\n";
        return 2;
    }
    const std::string data = argv[1], out = argv[2];
    const int seeds = std::atoi(argv[3]);
    registerAllClasses();
    std::vector<std::pair<std::string, Row>> rows;
    std::vector<std::pair<std::string, double>> repeatability;  // of seed 1's variant
    std::printf("Judged at %.2f m (passes: nodes within it of an earlier place; a closure right "
                "within it).\n\n", radius);
    std::printf(
        "| recording | INI | same-direction passes found | opposite-direction found | "
        "worst seed's recall: same / opposite | precision | closures | wrong | "
        "inside their own 99.73 %% (wrong ones) | ATE median / worst [m] | real-time factor |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& rec : benchRecordings(data)) {
        if (!only.empty() && rec.name.find(only) == std::string::npos) continue;
        const auto recording = rec.read();
        const std::string name = rec.name + (variant.empty() ? "" : " [" + variant + "]");
        repeatability.emplace_back(name, datasets::passRepeatability(datasets::magneticVariant(recording, variant, 1, out)));
        for (const auto& ini : inis) {
            Row row;
            for (int seed = 1; seed <= seeds; ++seed) {
                std::string stem = rec.name + "_s" + std::to_string(seed);
                std::replace(stem.begin(), stem.end(), ' ', '_');
                const auto imported =
                    importSeed(datasets::magneticVariant(recording, variant, unsigned(seed), out),
                               out + "/" + stem + ".rawlog", seed, driftScale);
                const auto run = runImported(imported, ini, out + "/" + stem + "_run");
                if (!run.ok()) {
                    std::cerr << name << " " << ini << ": " << run.errors;
                    return 1;
                }
                row.ate.push_back(*run.result.ateRmse);
                row.realtime.push_back(imported.duration / run.wallSeconds);
                judgeRun(run.options, row, radius);
            }
            char consistency[64] = "-";
            if (row.covarianceJudged) {
                std::snprintf(consistency, sizeof consistency, "%.3f (%zu)",
                              double(row.insideOwnRegion) / double(row.covarianceJudged),
                              row.wrongInsideOwnRegion);
            }
            std::printf(
                "| %s | %s | %s | %s | %s / %s | %s | %zu | %zu | %s | %.3f / %.3f | %.0fx |\n",
                name.c_str(), ini.c_str(), fraction(row.found[0], row.passes[0]).c_str(),
                fraction(row.found[1], row.passes[1]).c_str(), worstOf(row.worst[0]).c_str(),
                worstOf(row.worst[1]).c_str(),
                row.judged ? worstOf(double(row.right) / double(row.judged)).c_str() : "-",
                row.closures, row.wrong, consistency, median(row.ate),
                *std::max_element(row.ate.begin(), row.ate.end()), median(row.realtime));
            std::fflush(stdout);
            rows.emplace_back(name + " | " + ini, row);
        }
    }
    std::printf(
        "\nPasses each closer missed, by the furthest stage their true place reached in it "
        "(same / opposite direction, all seeds; stages with none left out):\n\n"
        "| recording | INI | closer | passes missed, by stage | truth inside the gate: mean / "
        "worst seed |\n|---|---|---|---|---|\n");
    for (const auto& [name, row] : rows)
        for (const auto& [decider, funnel] : row.funnels) {
            std::printf("| %s | %s | %s |", name.c_str(), decider.c_str(),
                        eval::missedByStage(funnel.missed).c_str());
            double sum = 0, worst = INFINITY;
            std::size_t n = 0;
            for (double v : funnel.insideGate) {
                if (!std::isfinite(v)) continue;
                sum += v;
                worst = std::min(worst, v);
                ++n;
            }
            std::printf(" %s / %s |\n", n ? worstOf(sum / double(n)).c_str() : "-",
                        worstOf(worst).c_str());
        }
    std::printf("\nHow readings at one place differ between passes, per component (readings within "
                "0.15 m by the truth, more than 5 m of walk apart; 1.4826 MAD / sqrt 2):");
    for (const auto& [name, sigma] : repeatability) std::printf(" %s %.2f uT;", name.c_str(), sigma);
    std::printf("\n");
    return 0;
}
