// A map of Aalto's room reused by later trials, measured through lodestone-slam's path (rawlogs
// imported to disk, --map-out, then --map-in --mode localize):
//   bench_aalto_maps DATA OUT_DIR [SLAM.ini] [--seeds N] [--trials 2,3,...]
// DATA is ../shared/data/magnetic (exits 0 with a note when it is absent); SLAM.ini a
// config_ini/ name or a path (default magnetic_window.ini). Trial 1 is mapped twice: with the
// drift model's odometry (seed 1: the map a robot makes alone - Aalto's trials seldom revisit
// their own path, so it is its odometry) and with the reference as odometry (a surveyed map).
// Each other trial, imported with the drift model for seeds 1..N, is localized in each map and
// judged in the map's frame (the map run aligned to its truth once, bench/map_runs.h): relocated
// or not, the travel to the first relocation, its error (wrong: more than 1 m off), the share of
// the run's nodes on the map within 0.3 m of the reference (also split: where the map has the
// place - within 0.3 m of trial 1's path - and elsewhere), and how far the map moved. Trials
// 6-9 were recorded after metal shelves were brought in: the map's field is partly wrong there.
#include <lodestone/eval/TrajectoryError.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/maps/SavedMap.h>
#include <lodestone/obs/registerAllClasses.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <vector>

#include "magnetic_recordings.h"
#include "map_runs.h"

using namespace lodestone;

namespace {

double median(std::vector<double> v) {
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

double worst(const std::vector<double>& v) {
    return v.empty() ? NAN : *std::max_element(v.begin(), v.end());
}

/** Where the map itself has the place the truth puts the robot at `t`: the map run's node at
 * the time its own truth passed nearest that place (within 0.3 m; else none). In a map made by
 * drifting odometry that place is not where the aligned reference is; a relocation is judged
 * against the map's own placement. */
std::optional<Eigen::Vector2d> mapPlace(const std::vector<io::TumPose>& runTruth, double t,
                                        const std::vector<io::TumPose>& mapTruth,
                                        const std::vector<io::TumPose>& mapNodes) {
    const auto* here = eval::truthAt(runTruth, t, 0.05);
    if (!here || mapTruth.empty() || mapNodes.empty()) return std::nullopt;
    const auto d2 = [&](const io::TumPose& p) {
        return std::pow(p.pose.x() - here->pose.x(), 2) + std::pow(p.pose.y() - here->pose.y(), 2);
    };
    const auto nearest =
        std::min_element(mapTruth.begin(), mapTruth.end(),
                         [&](const auto& a, const auto& b) { return d2(a) < d2(b); });
    if (d2(*nearest) > 0.09) return std::nullopt;
    const auto node =
        std::min_element(mapNodes.begin(), mapNodes.end(), [&](const auto& a, const auto& b) {
            return std::abs(a.timestamp - nearest->timestamp) <
                   std::abs(b.timestamp - nearest->timestamp);
        });
    return Eigen::Vector2d(node->pose.x(), node->pose.y());
}

/** The arguments left once --seeds N and --trials 2,3,... are taken out. */
struct CommandLine {
    std::vector<std::string> args;
    int seeds{3};
    std::vector<int> trials{2, 3, 4, 5, 6, 7, 8, 9};
    bool usable{true};  ///< false: a number that is none
};

CommandLine parseCommandLine(int argc, char** argv) {
    CommandLine cl;
    auto& args = cl.args;
    args.assign(argv + 1, argv + argc);
    int& seeds = cl.seeds;
    std::vector<int>& trials = cl.trials;
    bool& usable = cl.usable;
    for (std::size_t i = 0; usable && i + 1 < args.size();) {
        if (args[i] == "--seeds") {
            try {
                seeds = std::stoi(args[i + 1]);
            } catch (const std::exception&) {
                usable = false;
            }
        } else if (args[i] == "--trials") {
            trials.clear();
            std::stringstream ss(args[i + 1]);
            for (std::string t; usable && std::getline(ss, t, ',');) {
                try {
                    trials.push_back(std::stoi(t));
                } catch (const std::exception&) {
                    usable = false;
                }
            }
        } else {
            ++i;
            continue;
        }
        args.erase(args.begin() + static_cast<long>(i), args.begin() + static_cast<long>(i) + 2);
    }
    return cl;
}

}  // namespace

int main(int argc, char** argv) {
    const CommandLine cl = parseCommandLine(argc, argv);
    const auto& args = cl.args;
    const int seeds = cl.seeds;
    const std::vector<int>& trials = cl.trials;
    const bool usable = cl.usable;
    if (!usable || args.size() < 2 || seeds < 1 || trials.empty()) {
        std::cerr
            << "usage: bench_aalto_maps DATA OUT_DIR [SLAM.ini] [--seeds N] [--trials 2,3,...]\n";
        return 2;
    }
    const std::string data = args[0] + "/aalto/invensense", dir = args[1];
    const std::string config = args.size() > 2 ? args[2] : "magnetic_window.ini";
    if (!std::filesystem::is_directory(data)) {
        std::printf("bench_aalto_maps: %s is absent; nothing measured\n", data.c_str());
        return 0;
    }
    try {
        registerAllClasses();
        std::filesystem::create_directories(dir);
        for (const bool surveyed : {false, true}) {
            const std::string tag = surveyed ? "surveyed" : "own";
            const auto mapImport =
                importSeed(datasets::readAaltoTrial(data, 1), dir + "/" + tag + "_t1.rawlog", 1,
                           surveyed ? 0.0 : 1.0);
            const auto mapRun = runImported(mapImport, config, dir + "/" + tag + "_t1_out", "",
                                            dir + "/" + tag + "_map");
            if (mapRun.result.exitCode != 0) throw std::runtime_error("mapping: " + mapRun.errors);
            double mapAte = 0;
            const auto T_world_map =
                mapFrame(dir + "/" + tag + "_t1_out", mapImport.groundTruth, mapAte);
            const auto saved = maps::readMap(dir + "/" + tag + "_map");
            const auto mapTruth = io::readTumTrajectory(mapImport.groundTruth);
            const auto mapNodes = io::readTumTrajectory(dir + "/" + tag + "_t1_out/trajectory.tum");
            // Where the map holds the place: within 0.3 m of trial 1's reference path (its
            // field's fitted length scale is 0.22-0.32 m: further, the GP knows little).
            std::vector<Eigen::Vector2d> mapPath;
            for (const auto& p : mapTruth) mapPath.emplace_back(p.pose.x(), p.pose.y());
            const Coverage covered = nearPath(mapPath, 0.3);
            std::printf("\nMap: trial 1, %s - %zu nodes, its ATE %.3f m; %s, %d seeds\n\n",
                        surveyed ? "the reference as odometry (surveyed)"
                                 : "the drift model's odometry (seed 1)",
                        saved.nodes.size(), mapAte, config.c_str(), seeds);
            std::printf(
                "| trial | relocated | travel to it median / worst [m] | its error median / worst "
                "[m] "
                "| wrong (> 1 m) | error against the map's own place: median / worst [m] (judged) "
                "| wrong there (> 1 m) | nodes on the map within 0.3 m: mean / worst | ATE on the "
                "map "
                "median [m] | map moved [m] | nodes where the map has the place | of those within "
                "0.3 m / of the rest |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
            for (const int t : trials) {
                const auto rec = datasets::readAaltoTrial(data, t);
                std::vector<double> travel, error, within, ate, ownError, coveredShare,
                    withinCovered, withinUncovered;
                int relocated = 0, wrong = 0, ownWrong = 0;
                double moved = 0;
                for (int seed = 1; seed <= seeds; ++seed) {
                    const std::string stem =
                        dir + "/" + tag + "_t" + std::to_string(t) + "_s" + std::to_string(seed);
                    const auto imported = importSeed(rec, stem + ".rawlog", seed);
                    const auto r =
                        runImported(imported, config, stem + "_out", dir + "/" + tag + "_map");
                    if (r.result.exitCode != 0) throw std::runtime_error(stem + ": " + r.errors);
                    const auto j =
                        judgeMapRun(stem + "_out", imported.groundTruth, saved, T_world_map, 0.3,
                                    covered);
                    moved = std::max(moved, j.moved);
                    if (std::isfinite(j.coveredShare)) coveredShare.push_back(j.coveredShare);
                    if (std::isfinite(j.withinCovered)) withinCovered.push_back(j.withinCovered);
                    if (std::isfinite(j.withinUncovered))
                        withinUncovered.push_back(j.withinUncovered);
                    within.push_back(std::isfinite(j.within) ? j.within : 0.0);
                    if (!j.relocated) continue;
                    ++relocated;
                    travel.push_back(j.travel);
                    error.push_back(j.errorXY);
                    wrong += !(j.errorXY <= 1.0);
                    if (const auto place = mapPlace(io::readTumTrajectory(imported.groundTruth),
                                                    j.relocationTime, mapTruth, mapNodes)) {
                        ownError.push_back(std::hypot(j.relocatedPose.x() - place->x(),
                                                      j.relocatedPose.y() - place->y()));
                        ownWrong += ownError.back() > 1.0;
                    }
                    if (std::isfinite(j.ate)) ate.push_back(j.ate);
                }
                const auto mean = [](const std::vector<double>& v) {
                    double m = 0;
                    for (double w : v) m += w / double(v.size());
                    return v.empty() ? NAN : m;
                };
                const double meanWithin = mean(within);
                std::printf(
                    "| %d | %d/%d | %.2f / %.2f | %.3f / %.3f | %d | %.3f / %.3f (%zu) | %d | %.2f "
                    "/ %.2f "
                    "| %.3f | %.4f | %.2f | %.2f / %.2f |\n",
                    t, relocated, seeds, median(travel), worst(travel), median(error), worst(error),
                    wrong, median(ownError), worst(ownError), ownError.size(), ownWrong, meanWithin,
                    *std::min_element(within.begin(), within.end()), median(ate), moved,
                    mean(coveredShare), mean(withinCovered), mean(withinUncovered));
                std::fflush(stdout);
            }
        }
    } catch (const std::exception& e) {
        std::cerr << "bench_aalto_maps: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
