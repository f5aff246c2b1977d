// What a large map costs: a long magnetic walk (bench/magnetic_recordings.h: laps of a 40 m x
// 20 m rectangle at 1.2 m/s, a node every 0.1 m) mapped with --map-out, then
//  - loading it (maps::readMap, median of three) and what it takes on disk and in memory;
//  - a later two-lap walk (another drift seed) localized in it: the time per query and per node,
//    the real-time factor, how far it went before it knew where it was;
//  - SESSIONS one-lap walks each extending the map in turn: the time per node of each session
//    (flat, or growing with the map).
//   bench_map_scale OUT_DIR LAPS SESSIONS [SLAM.ini]   (default magnetic_window.ini)
#include <lodestone/datasets/MagneticRecordingImport.h>
#include <lodestone/maps/SavedMap.h>
#include <lodestone/obs/registerAllClasses.h>
#include <lodestone/slamapp/SlamRun.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <malloc.h>
#include <regex>
#include <sstream>

#include "bench_reports.h"
#include "magnetic_recordings.h"

using namespace lodestone;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

/** Heap bytes in use (glibc's mallinfo2): what a loaded map holds, whatever pages the
 * allocator kept from before. */
double heapInUse() { return static_cast<double>(mallinfo2().uordblks + mallinfo2().hblkhd); }

struct Timed {
    double seconds{0}, duration{0};
    std::string out;
};

/** `laps` laps imported with drift `seed`, run from disk with the map options given. */
Timed runWalk(const std::string& dir, const std::string& name, int laps, int seed,
              const std::string& config, const std::string& mapIn, const std::string& mapOut,
              bool extend) {
    datasets::OdometryDriftModel model;
    model.seed = static_cast<std::uint64_t>(seed);
    const auto imported =
        datasets::writeMagneticRecording(syntheticLongWalk(laps), dir + "/" + name + ".rawlog", model);
    slamapp::SlamRunOptions o;
    o.rawlog = imported.rawlog;
    // (no ground truth: its diagnostics - the loop closers' recall funnels - are not a user's
    // cost, and nothing here is judged against it)
    o.config = config;
    o.outDir = dir + "/" + name;
    o.mapIn = mapIn;
    o.mapOut = mapOut;
    o.extendMap = extend;
    o.quiet = true;
    std::ostringstream out, err;
    const auto t0 = Clock::now();
    const auto r = slamapp::runSlam(o, out, err);
    Timed t;
    t.seconds = secondsSince(t0);
    t.duration = imported.duration;
    t.out = o.outDir;
    if (r.exitCode != 0) throw std::runtime_error(name + ": " + err.str());
    return t;
}

std::size_t bytesOnDisk(const std::string& dir) {
    std::size_t n = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.is_regular_file()) n += e.file_size();
    return n;
}

/** Engine ms of each of the run's own nodes (nodes.csv's engine_ms after the map's). */
std::vector<double> msOfRunNodes(const std::string& out, std::size_t mapNodes) {
    std::ifstream in(out + "/nodes.csv");
    std::string line;
    std::getline(in, line);
    std::vector<double> ms;
    for (std::size_t id = 0; std::getline(in, line); ++id) {
        if (id < mapNodes) continue;
        const auto v = std::stod(line.substr(line.find_last_of(',') + 1));
        if (std::isfinite(v)) ms.push_back(v);
    }
    return ms;
}

double msPerRunNode(const std::string& out, std::size_t mapNodes) {
    const auto ms = msOfRunNodes(out, mapNodes);
    double sum = 0;
    for (const double v : ms) sum += v;
    return ms.empty() ? NAN : sum / double(ms.size());
}

/** The run's per-node engine ms at quantile q (0.5: the median). */
double msQuantile(const std::string& out, std::size_t mapNodes, double q) {
    auto ms = msOfRunNodes(out, mapNodes);
    if (ms.empty()) return NAN;
    const auto at = ms.begin() + static_cast<long>(q * double(ms.size() - 1));
    std::nth_element(ms.begin(), at, ms.end());
    return *at;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::cerr << "usage: bench_map_scale OUT_DIR LAPS SESSIONS [SLAM.ini]\n";
        return 2;
    }
    try {
        registerAllClasses();
        const std::string dir = argv[1];
        const int laps = std::atoi(argv[2]), sessions = std::atoi(argv[3]);
        const std::string config =
            argc > 4 ? argv[4] : std::string(LODESTONE_CONFIG_INI_DIR) + "/slam/magnetic_window.ini";
        const std::string map = dir + "/map";
        const auto made = runWalk(dir, "mapping", laps, 1, config, "", map, false);

        // Loading: the median of three; memory held by the loaded map.
        std::vector<double> loads;
        double heldBytes = 0;
        std::size_t nodes = 0;
        for (int k = 0; k < 3; ++k) {
            const double before = heapInUse();
            const auto t0 = Clock::now();
            const auto loaded = maps::readMap(map);
            loads.push_back(secondsSince(t0));
            heldBytes = std::max(heldBytes, heapInUse() - before);
            nodes = loaded.nodes.size();
        }
        std::sort(loads.begin(), loads.end());
        const std::size_t disk = bytesOnDisk(map);
        std::printf("| map | nodes | data [min] | mapped at | load [s] | on disk [MB] | bytes a node on disk | heap bytes a node, loaded |\n|---|---|---|---|---|---|---|---|\n");
        std::printf("| %d laps | %zu | %.1f | %.0fx real time | %.3f | %.1f | %.0f | %.0f |\n\n", laps,
                    nodes, made.duration / 60, made.duration / made.seconds, loads[1],
                    double(disk) / 1e6, double(disk) / double(nodes), heldBytes / double(nodes));

        // Localizing a two-lap walk in it.
        const auto walk = runWalk(dir, "localize", 2, 2, config, map, "", false);
        const std::string report = slurp(walk.out + "/report.json");
        std::printf("| localized walk | travel to relocation [m] | query ms mean / max | engine ms a node | real-time factor |\n|---|---|---|---|---|\n");
        std::printf("| 2 laps, drift seed 2 | %.1f | %.2f / %.1f | %.2f | %.0fx |\n\n",
                    numberIn(report, "travel_to_relocation_m"), numberIn(report, "query_ms_mean"),
                    numberIn(report, "query_ms_max"), msPerRunNode(walk.out, nodes),
                    walk.duration / walk.seconds);

        // Sessions extending the map in turn.
        std::printf("| session | map nodes before | map readings: targets / all | engine ms a node: mean / median / 95 %% | real-time factor | relocated after [m] |\n|---|---|---|---|---|---|\n");
        std::string current = map;
        for (int s = 1; s <= sessions; ++s) {
            const std::size_t before = maps::readMap(current).nodes.size();
            const std::string next = dir + "/map_" + std::to_string(s);
            const auto t = runWalk(dir, "session_" + std::to_string(s), 1, 10 + s, config, current,
                                   next, true);
            const std::string report = slurp(t.out + "/report.json");
            const double all = numberIn(report, "map_readings");
            std::printf("| %d | %zu | %.0f / %.0f | %.2f / %.2f / %.2f | %.0fx | %.1f |\n", s,
                        before, all - numberIn(report, "map_readings_thinned"), all,
                        msPerRunNode(t.out, before), msQuantile(t.out, before, 0.5),
                        msQuantile(t.out, before, 0.95), t.duration / t.seconds,
                        numberIn(report, "travel_to_relocation_m"));
            std::fflush(stdout);
            current = next;
        }
    } catch (const std::exception& e) {
        std::cerr << "bench_map_scale: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
