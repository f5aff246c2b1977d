// The visual loop closer (OrbSubmapERD, paper 000 §2.1) on a simulated scenario, against the
// simulator's ground truth. Prints markdown rows (to stdout, each table's rows prefixed by its
// name, which scripts/bench/visual.sh sorts into tables):
//   CLOSURES scenario | submaps of | keyframes | submaps | closures | false (> 0.2 m or 5 deg) |
//            phase 2 used | phase-2 error median [cm / deg] | closures per lap | textured
//            revisits with a closure | ATE [m] (odometry only: see slam.sh)
//   PLAIN    scenario | submaps of | plain-view queries | best phase-1 matches (mean) |
//            inliers (mean) | closures from plain views
//   TIME     scenario | submaps of | candidates | match ms per candidate: mean / max |
//            retrieval ms per query: mean / max
//   bench_visual SCENARIO.ini VISUAL.ini [KEYFRAMES_PER_SUBMAP] [WIDTHxHEIGHT@HZ|-]
// KEYFRAMES_PER_SUBMAP overrides submap_max_keyframes (1: single keyframes, no submaps).
#include <lodestone/eval/TrajectoryError.h>
#include <lodestone/graphslam/erd/CompositeERD.h>
#include <lodestone/graphslam/nrd/FusedOdometryNRD.h>
#include <lodestone/graphslam/erd/visual/OrbSubmapERD.h>
#include <lodestone/graphslam/SlamEngine.h>
#include <lodestone/sim/RobotConfig.h>
#include <lodestone/sim/RgbdRenderer.h>
#include <lodestone/sim/SimulatorSource.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <regex>
#include <sstream>

using namespace lodestone;

namespace {
Eigen::Isometry3d isometry(const sim::RobotPose& p) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(p.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(p.x, p.y, 0);
    return T;
}
double median(std::vector<double> v) {
    if (v.empty()) return NAN;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

/** Maximal runs of textured keyframes after the first lap, and how many of them got a
 * closure. */
std::pair<std::size_t, std::size_t> closedRevisits(
    const graphslam::NodeStore& nodes, const std::function<int(graphslam::TNodeID)>& lapOf,
    const std::function<bool(graphslam::TNodeID)>& textured, const std::vector<char>& closedAt) {
    std::size_t runs = 0, runsClosed = 0;
    bool inRun = false, runClosed = false;
    for (graphslam::TNodeID id = 0; id < nodes.size(); ++id) {
        if (!nodes.at(id).keyframe || lapOf(id) == 0) continue;
        const bool tex = textured(id);
        if (tex && !inRun) {
            inRun = true;
            runClosed = false;
            ++runs;
        }
        if (tex && closedAt[id] && !runClosed) {
            runClosed = true;
            ++runsClosed;
        }
        if (!tex) inRun = false;
    }
    return {runs, runsClosed};
}

/** PLAIN: what matching achieves from a keyframe that sees mostly plain wall; TIME: the
 * matching's and retrieval's cost. */
void printPlainViewsAndTime(const graphslam::OrbSubmapERD& erd,
                            const std::function<bool(graphslam::TNodeID)>& textured,
                            const std::string& scenario, const std::string& kindText) {
    const auto& st = erd.stats();
    std::size_t plainQueries = 0, plainClosures = 0;
    double plainMatches = 0, plainInliers = 0;
    double matchMax = 0, retrievalMax = 0, retrievalSum = 0;
    for (const auto& q : erd.queries()) {
        matchMax = std::max(matchMax, q.slowestMatchMs);
        retrievalMax = std::max(retrievalMax, q.retrievalMs);
        retrievalSum += q.retrievalMs;
        if (q.candidates == 0 || textured(q.node)) continue;
        ++plainQueries;
        plainMatches += q.bestMatches;
        plainInliers += q.bestInliers;
        plainClosures += q.accepted;
    }
    std::printf("PLAIN | %s | %s | %zu | %.1f | %.1f | %zu |\n", scenario.c_str(), kindText.c_str(),
                plainQueries, plainQueries ? plainMatches / plainQueries : 0.0,
                plainQueries ? plainInliers / plainQueries : 0.0, plainClosures);
    std::printf("TIME | %s | %s | %zu | %.2f / %.2f | %.3f / %.3f |\n", scenario.c_str(),
                kindText.c_str(), st.candidatesTried,
                st.candidatesTried ? st.matchMs / st.candidatesTried : 0.0, matchMax,
                erd.queries().empty() ? 0.0 : retrievalSum / erd.queries().size(), retrievalMax);
}
}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::cerr << "usage: bench_visual SCENARIO.ini VISUAL.ini [KEYFRAMES_PER_SUBMAP] [WxH@HZ|-]\n";
        return 2;
    }
    try {
        sim::Scenario sc = sim::Scenario::load(argv[1]);
        if (argc > 4 && std::string(argv[4]) != "-") {
            if (!sc.camera.override(argv[4])) throw std::runtime_error("bad camera: expected WxH@HZ");
        }
        std::ifstream in(argv[2]);
        std::stringstream text;
        text << in.rdbuf();
        std::string ini = text.str();
        std::string perSubmap = "6";
        if (argc > 3) {
            perSubmap = argv[3];
            ini = std::regex_replace(ini, std::regex("submap_max_keyframes *= *[0-9]+"),
                                     "submap_max_keyframes = " + perSubmap);
        }
        const mrpt::config::CConfigFileMemory cfg(ini);
        auto engine = graphslam::SlamEngine::fromConfig(sim::withScenarioWheels(cfg, sc, argv[2]));
        const auto& composite = dynamic_cast<graphslam::CompositeERD&>(engine->edgeDecider());
        const auto* erd = dynamic_cast<const graphslam::OrbSubmapERD*>(composite.children().at(0).get());
        if (!erd) throw std::runtime_error("the INI's first loop closer is not OrbSubmapERD");

        sim::SimulatorSource source(sc, sc.seed);
        while (auto obs = source.next()) engine->process(obs);
        engine->finish();

        // Ground truth per node; laps by distance travelled.
        const auto& nodes = engine->nodes();
        std::vector<Eigen::Isometry3d> truth;
        std::vector<double> travelled;
        std::vector<io::TumPose> est, gt;
        for (graphslam::TNodeID id = 0; id < nodes.size(); ++id) {
            const double t = nodes.at(id).timestamp;
            const auto p = source.truePose(t - sc.startTime);
            truth.push_back(isometry(p));
            travelled.push_back(id ? travelled.back() + (truth[id].translation() - truth[id - 1].translation()).norm() : 0);
            est.push_back({t, engine->graph().nodes.at(id)});
            gt.push_back({t, mrpt::poses::CPose3D(p.x, p.y, 0, p.yaw, 0, 0)});
        }
        const int laps = std::max(1, sc.motion.laps);
        const double lapLength = travelled.back() / laps;
        const auto lapOf = [&](graphslam::TNodeID id) {
            return std::min(laps - 1, static_cast<int>(travelled[id] / lapLength));
        };
        // What each node's camera faces, from the world itself.
        const sim::RgbdRenderer truthRenderer(source.world(), sc.camera, 1);
        const auto textured = [&](graphslam::TNodeID id) {
            const auto p = source.truePose(nodes.at(id).timestamp - sc.startTime);
            const auto& cm = sc.camera.pose;
            const auto cs = sim::sensorInWorld(p, cm.x, cm.y, cm.z, cm.yaw);
            return truthRenderer.texturedFraction(cs.position, cs.yaw) >= 0.5;
        };

        std::size_t falseClosures = 0, phase2 = 0;
        std::vector<double> errCm, errDeg;
        std::vector<int> perLap(static_cast<std::size_t>(laps), 0);
        std::vector<char> closedAt(nodes.size(), 0);
        for (const auto& r : erd->records()) {
            const Eigen::Isometry3d trueRel = truth[r.from].inverse() * truth[r.to];
            const Eigen::Isometry3d d = trueRel.inverse() * r.relative;
            const double cm = 100 * std::hypot(d.translation().x(), d.translation().y());
            const double deg = std::abs(std::atan2(d.linear()(1, 0), d.linear()(0, 0))) * 180 / M_PI;
            if (cm > 20 || deg > 5) {
                ++falseClosures;
                std::fprintf(stderr, "false closure %zu -> %zu: %.1f cm, %.2f deg, phase %d, %zu inliers\n",
                             static_cast<std::size_t>(r.from), static_cast<std::size_t>(r.to), cm, deg,
                             r.phase2 ? 2 : 1, r.phase2 ? r.phase2Inliers : r.inliers);
            }
            if (r.phase2) {
                ++phase2;
                errCm.push_back(cm);
                errDeg.push_back(deg);
            }
            ++perLap[static_cast<std::size_t>(lapOf(r.to))];
            closedAt[r.to] = 1;
        }
        // Textured revisits: maximal runs of textured keyframes after the first lap; how many
        // got at least one closure.
        const auto [runs, runsClosed] = closedRevisits(nodes, lapOf, textured, closedAt);
        std::string lapText;
        for (int l = 0; l < laps; ++l) lapText += (l ? " / " : "") + std::to_string(perLap[static_cast<std::size_t>(l)]);
        const auto ate = eval::absoluteTrajectoryError(est, gt);
        const auto& st = erd->stats();
        const std::string kindText = perSubmap == "1" ? "1 keyframe" : perSubmap + " keyframes";
        std::printf("CLOSURES | %s | %s | %zu | %zu | %zu | %zu | %zu | %.1f cm / %.2f deg | %s | %zu of %zu | %.3f |\n",
                    sc.name.c_str(), kindText.c_str(), st.keyframes, st.submaps, st.accepted,
                    falseClosures, phase2, median(errCm), median(errDeg), lapText.c_str(),
                    runsClosed, runs, ate.rmse);

        printPlainViewsAndTime(*erd, textured, sc.name, kindText);
    } catch (const std::exception& e) {
        std::cerr << "bench_visual: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
