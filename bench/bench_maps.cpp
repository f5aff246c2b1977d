// Maps that outlive a run, measured: a scenario mapped once (its laps, seed 1, simulated to a
// rawlog and run from disk with --map-out), then later runs of one lap started in that map with
// --map-in (localize) - other seeds, other start points, driven the other way, in the same
// building (Scenario::worldSeed) - each judged in the map's frame against the simulator's truth
// with no re-alignment: the map's frame is tied to the world once, by the map run's own nodes
// aligned to its truth (what is left of the map's error, its ATE, stays in every figure).
//   bench_maps OUT_DIR SCENARIO.ini SLAM.ini [WIDTHxHEIGHT@HZ]
// A markdown row per run: start, seed, relocated, travel to the first relocation [m], its error
// [m, deg] (wrong: more than 0.5 m or 10 deg), ATE of the run's nodes on the map in the map's
// frame [m], nodes on the map / all, how far the map's nodes moved [m], real-time factor.
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

using namespace lodestone;

namespace {

struct Variant {
    std::string start;  ///< what the table says of it
    std::uint64_t seed;
    std::size_t firstWaypoint;  ///< the loop entered at this waypoint
    bool reversed;              ///< the loop driven the other way round
};

std::string slurp(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

double numberIn(const std::string& text, const std::string& key) {
    std::smatch m;
    if (!std::regex_search(text, m, std::regex("\"" + key + "\": (-?[0-9.eE+-]+)"))) return NAN;
    return std::stod(m[1]);
}

/** Records `scenario` as OUT.rawlog (+ .gt.tum), then runs lodestone-slam's code path on it. */
struct Run {
    slamapp::SlamRunResult result;
    std::string out, truth;
    double seconds{0}, duration{0};
};

Run record(sim::Scenario scenario, std::uint64_t seed, const std::string& stem) {
    sim::SimulatorSource source(scenario, seed);
    const auto summary = sim::recordScenario(source, stem + ".rawlog");
    Run r;
    r.truth = summary.groundTruth;
    r.duration = summary.duration;
    return r;
}

Run slam(Run r, const std::string& stem, const std::string& config, const std::string& mapOut,
         const std::string& mapIn) {
    slamapp::SlamRunOptions o;
    o.rawlog = stem + ".rawlog";
    o.groundTruth = r.truth;
    o.config = config;
    o.outDir = stem + "_out";
    o.mapOut = mapOut;
    o.mapIn = mapIn;
    o.quiet = true;
    std::ostringstream out, err;
    const auto t0 = std::chrono::steady_clock::now();
    r.result = slamapp::runSlam(o, out, err);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.out = o.outDir;
    if (r.result.exitCode != 0) throw std::runtime_error(stem + ": " + err.str());
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::cerr << "usage: bench_maps OUT_DIR SCENARIO.ini SLAM.ini [WIDTHxHEIGHT@HZ]\n";
        return 2;
    }
    try {
        registerAllClasses();
        const std::string dir = argv[1], config = argv[3];
        sim::Scenario base = sim::Scenario::load(argv[2]);
        if (argc > 4 && !base.camera.override(argv[4]))
            throw std::runtime_error("bad camera: expected WxH@HZ");
        base.kidnaps.clear();
        base.worldSeed = 1;  // one building; every run its own sensor noise

        // The map: the scenario's laps, seed 1; every later run: one lap.
        const Run mapRun =
            slam(record(base, 1, dir + "/map_run"), dir + "/map_run", config, dir + "/map", "");
        base.motion.laps = 1;
        const auto saved = maps::readMap(dir + "/map");
        // The map's frame in the world: the map run's nodes aligned to its truth, once.
        const auto mapAte = eval::absoluteTrajectoryError(
            io::readTumTrajectory(mapRun.out + "/trajectory.tum"), io::readTumTrajectory(mapRun.truth));
        const mrpt::poses::CPose3D T_world_map(
            mrpt::math::CMatrixDouble44(mapAte.alignment.matrix()));
        std::printf("The map: %zu nodes, its own ATE %.3f m (aligned once: the map's frame)\n\n",
                    saved.nodes.size(), mapAte.rmse);

        const std::size_t n = base.motion.waypoints.size();
        const std::vector<Variant> variants = {
            {"the map's start, its way", 2, 0, false},
            {"the map's start, its way", 3, 0, false},
            {"another corner, its way", 4, 2, false},
            {"another corner, its way", 5, 1, false},
            {"the map's start, the other way", 6, 0, true},
            {"another corner, the other way", 7, 2, true},
        };
        std::printf(
            "| start | seed | relocated | travel to relocation [m] | relocation error [m / deg] "
            "| ATE in the map's frame [m] | nodes on the map / run | map moved [m] | real-time "
            "factor |\n|---|---|---|---|---|---|---|---|---|\n");
        for (const auto& v : variants) {
            sim::Scenario sc = base;
            auto& w = sc.motion.waypoints;
            std::rotate(w.begin(), w.begin() + static_cast<long>(v.firstWaypoint % n), w.end());
            if (v.reversed) std::reverse(w.begin() + 1, w.end());
            const std::string stem = dir + "/run_" + std::to_string(v.seed);
            const Run run = slam(record(sc, v.seed, stem), stem, config, "", dir + "/map");
            const auto truth = io::readTumTrajectory(run.truth);
            // (the first kidnap record: the run's start in the map)
            const std::string all = slurp(run.out + "/report.json");
            const std::string report = all.substr(std::min(all.size(), all.find("\"kidnaps\"")));
            const bool relocated = report.find("\"relocated\": true") != std::string::npos;
            const double travel = numberIn(report, "travel_to_relocation_m");
            std::string error = "-";
            if (relocated) {
                const mrpt::poses::CPose3D at(numberIn(report, "x"), numberIn(report, "y"), 0,
                                              numberIn(report, "yaw"), 0, 0);
                if (const auto* t = eval::truthAt(truth, numberIn(report, "relocation_time"), 0.05)) {
                    const auto e = (-t->pose) + (T_world_map + at);
                    char b[64];
                    std::snprintf(b, sizeof b, "%.3f / %.2f", std::hypot(e.x(), e.y()),
                                  std::abs(e.yaw()) * 180 / M_PI);
                    error = b;
                }
            }
            // The run's nodes on the map, in the map's frame, against the truth: no alignment.
            const auto onMap = io::readTumTrajectory(run.out + "/trajectory.tum");
            double sum = 0;
            std::size_t pairs = 0;
            for (const auto& p : onMap) {
                const auto* t = eval::truthAt(truth, p.timestamp, 0.05);
                if (!t) continue;
                const auto world = T_world_map + p.pose;
                sum += std::pow(world.x() - t->pose.x(), 2) + std::pow(world.y() - t->pose.y(), 2);
                ++pairs;
            }
            // The map's nodes: where the run left them (graph.graph) against where they were.
            graphslam::Graph after;
            after.loadFromTextFile(run.out + "/graph.graph");
            double moved = 0;
            for (const auto& [id, pose] : saved.graph.nodes) {
                const auto& a = after.nodes.at(id);
                moved = std::max(moved, std::hypot(a.x() - pose.x(), a.y() - pose.y()));
            }
            char ate[32] = "-";
            if (pairs) std::snprintf(ate, sizeof ate, "%.3f", std::sqrt(sum / double(pairs)));
            std::printf("| %s | %llu | %s | %s | %s | %s | %zu / %zu | %.4f | %.0fx |\n",
                        v.start.c_str(), static_cast<unsigned long long>(v.seed),
                        relocated ? "yes" : "no",
                        std::isfinite(travel) ? std::to_string(travel).substr(0, 5).c_str() : "-",
                        error.c_str(), ate, onMap.size(), run.result.nodes - saved.nodes.size(),
                        moved, run.duration / run.seconds);
            std::fflush(stdout);
        }
    } catch (const std::exception& e) {
        std::cerr << "bench_maps: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
