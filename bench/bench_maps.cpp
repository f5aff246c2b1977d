// Maps that outlive a run, measured: a scenario mapped once (its laps, seed 1, simulated to a
// rawlog and run from disk with --map-out), then later runs of one lap started in that map with
// --map-in - in the same building (Scenario::worldSeed), each judged in the map's frame against
// the simulator's truth with no re-alignment: the map's frame is tied to the world once, by the
// map run's own nodes aligned to its truth (what is left of the map's error, its ATE, stays in
// every figure).
//   bench_maps OUT_DIR SCENARIO.ini SLAM.ini [WIDTHxHEIGHT@HZ] [--extend "x y x y ..."]
// Without --extend: six localize runs - other seeds, another corner, driven the other way.
// With --extend ROUTE (a closed loop of waypoints through places the map never saw): one run
// extends the map along it (--mode extend --map-out), then one localizes in the extended map
// starting on the new part.
// A markdown row per run: what it was, seed, relocated, travel to the first relocation [m], its
// error [m, deg] (wrong: more than 0.5 m or 10 deg), ATE of the run's nodes on the map in the
// map's frame [m], nodes on the map / all, how far the loaded map's nodes moved [m], real-time
// factor.
#include <lodestone/eval/TrajectoryError.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/maps/SavedMap.h>
#include <lodestone/obs/registerAllClasses.h>
#include <lodestone/sim/ScenarioRecorder.h>
#include <lodestone/slamapp/SlamRun.h>

#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/poses/CPose3D.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>

#include "map_runs.h"

using namespace lodestone;

namespace {

struct Run {
    slamapp::SlamRunResult result;
    std::string out, truth;
    double seconds{0}, duration{0};
};

/** Records `scenario` as STEM.rawlog (+ .gt.tum) for `seed`, then runs lodestone-slam's code
 * path on it from disk. */
Run run(const sim::Scenario& scenario, std::uint64_t seed, const std::string& stem,
        const std::string& config, const std::string& mapOut, const std::string& mapIn,
        bool extend) {
    sim::SimulatorSource source(scenario, seed);
    const auto summary = sim::recordScenario(source, stem + ".rawlog");
    Run r;
    r.truth = summary.groundTruth;
    r.duration = summary.duration;
    slamapp::SlamRunOptions o;
    o.rawlog = stem + ".rawlog";
    o.groundTruth = r.truth;
    o.config = config;
    o.outDir = stem + "_out";
    o.mapOut = mapOut;
    o.mapIn = mapIn;
    o.extendMap = extend;
    o.quiet = true;
    std::ostringstream out, err;
    const auto t0 = std::chrono::steady_clock::now();
    r.result = slamapp::runSlam(o, out, err);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.out = o.outDir;
    if (r.result.exitCode != 0) throw std::runtime_error(stem + ": " + err.str());
    return r;
}

void printHeader() {
    std::printf(
        "| run | seed | relocated | travel to relocation [m] | relocation error [m / deg] | ATE "
        "in the map's frame [m] | nodes on the map / run | loaded map moved [m] | real-time "
        "factor |\n|---|---|---|---|---|---|---|---|---|\n");
}

/** One row: `r` (a run started in `loaded`) judged in the map's frame `T_world_map`. */
void printRow(const std::string& what, std::uint64_t seed, const Run& r,
              const maps::SavedMap& loaded, const mrpt::poses::CPose3D& T_world_map) {
    const auto j = judgeMapRun(r.out, r.truth, loaded, T_world_map);
    char error[64] = "-";
    if (std::isfinite(j.errorXY))
        std::snprintf(error, sizeof error, "%.3f / %.2f", j.errorXY, j.errorYawDeg);
    char ate[32] = "-", travelText[32] = "-";
    if (std::isfinite(j.ate)) std::snprintf(ate, sizeof ate, "%.3f", j.ate);
    if (std::isfinite(j.travel)) std::snprintf(travelText, sizeof travelText, "%.2f", j.travel);
    std::printf("| %s | %llu | %s | %s | %s | %s | %zu / %zu | %.4f | %.0fx |\n", what.c_str(),
                static_cast<unsigned long long>(seed), j.relocated ? "yes" : "no", travelText, error,
                ate, j.onMap, r.result.nodes - loaded.nodes.size(), j.moved,
                r.duration / r.seconds);
    std::fflush(stdout);
}

/** Six one-lap runs localized in the map: other seeds, another corner, the other way round. */
void localizeVariants(const std::string& dir, sim::Scenario base, const std::string& config,
                      const maps::SavedMap& saved, const mrpt::poses::CPose3D& T_world_map) {
    struct Variant {
        std::string what;
        std::uint64_t seed;
        std::size_t firstWaypoint;  ///< the loop entered at this waypoint
        bool reversed;              ///< the loop driven the other way round
    };
    const std::vector<Variant> variants = {
        {"the map's start, its way", 2, 0, false},
        {"the map's start, its way", 3, 0, false},
        {"another corner, its way", 4, 2, false},
        {"another corner, its way", 5, 1, false},
        {"the map's start, the other way", 6, 0, true},
        {"another corner, the other way", 7, 2, true},
    };
    const std::size_t n = base.motion.waypoints.size();
    printHeader();
    for (const auto& v : variants) {
        sim::Scenario sc = base;
        auto& w = sc.motion.waypoints;
        std::rotate(w.begin(), w.begin() + static_cast<long>(v.firstWaypoint % n), w.end());
        if (v.reversed) std::reverse(w.begin() + 1, w.end());
        const std::string stem = dir + "/run_" + std::to_string(v.seed);
        printRow(v.what, v.seed, run(sc, v.seed, stem, config, "", dir + "/map", false), saved,
                 T_world_map);
    }
}

/** The map extended along `route` (seed 2), then a run localized in the extended map from the
 * route's first waypoint off the old map (seed 3). */
void extendAlong(const std::string& dir, sim::Scenario base, const std::string& config,
                 const maps::SavedMap& saved, const mrpt::poses::CPose3D& T_world_map,
                 const std::vector<Eigen::Vector2d>& route, std::size_t firstNew) {
    printHeader();
    sim::Scenario sc = base;
    sc.motion.waypoints = route;
    const Run extend =
        run(sc, 2, dir + "/extend", config, dir + "/map_extended", dir + "/map", true);
    printRow("extend along the route", 2, extend, saved, T_world_map);
    const auto extended = maps::readMap(dir + "/map_extended");
    std::rotate(sc.motion.waypoints.begin(),
                sc.motion.waypoints.begin() + static_cast<long>(firstNew % route.size()),
                sc.motion.waypoints.end());
    printRow("localize in the extended map, from the new part", 3,
             run(sc, 3, dir + "/again", config, "", dir + "/map_extended", false), extended,
             T_world_map);
    std::printf("\nThe extended map: %zu nodes (%zu added), %u sessions\n", extended.nodes.size(),
                extended.nodes.size() - saved.nodes.size(), extended.manifest.sessions);
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    std::vector<Eigen::Vector2d> route;
    std::size_t firstNew = 0;
    for (std::size_t i = 0; i + 1 < args.size(); ++i) {
        if (args[i] != "--extend") continue;
        std::istringstream xy(args[i + 1]);
        for (double x, y; xy >> x >> y;) route.emplace_back(x, y);
        if (args.size() > i + 2) firstNew = std::stoul(args[i + 2]);
        args.erase(args.begin() + static_cast<long>(i), args.end());
        break;
    }
    if (args.size() < 3) {
        std::cerr << "usage: bench_maps OUT_DIR SCENARIO.ini SLAM.ini [WIDTHxHEIGHT@HZ] "
                     "[--extend \"x y x y ...\" FIRST_NEW_WAYPOINT]\n";
        return 2;
    }
    try {
        registerAllClasses();
        const std::string dir = args[0], config = args[2];
        sim::Scenario base = sim::Scenario::load(args[1]);
        if (args.size() > 3 && !base.camera.override(args[3]))
            throw std::runtime_error("bad camera: expected WxH@HZ");
        base.kidnaps.clear();
        base.worldSeed = 1;  // one building; every run its own sensor noise

        // The map: the scenario's laps, seed 1; every later run: one lap.
        const Run mapRun = run(base, 1, dir + "/map_run", config, dir + "/map", "", false);
        base.motion.laps = 1;
        const auto saved = maps::readMap(dir + "/map");
        double mapAte = 0;
        const auto T_world_map = mapFrame(mapRun.out, mapRun.truth, mapAte);
        std::printf("The map: %zu nodes, its own ATE %.3f m (aligned once: the map's frame)\n\n",
                    saved.nodes.size(), mapAte);
        if (route.empty()) {
            localizeVariants(dir, base, config, saved, T_world_map);
        } else {
            extendAlong(dir, base, config, saved, T_world_map, route, firstNew);
        }
    } catch (const std::exception& e) {
        std::cerr << "bench_maps: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
