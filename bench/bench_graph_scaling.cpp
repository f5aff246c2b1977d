// The engine and CeresGSO on synthetic pose graphs of growing size (SyntheticGraph: laps of a
// square with loop closures on every revisit), replayed node by node: engine time per node by
// decile of the run, to show it does not grow with the graph. MRPT's CGraphSlamEngine measured
// 50-60 ms per node at 5 000 nodes on this machine (MRPT_NOTES.md).
// Prints one markdown row per size:
//   closures to | nodes | closures | local / full solves | escalations | rejected | local / full solve time [s] |
//   ms per node: mean, p99, by decile | final full solve [s] | position RMSE vs truth [m]
//   (dead reckoning [m])
//   bench_graph_scaling first|previous [NODES ...]   (default 1000 5000 10000): closures to the
//   first lap (every revisit of a place piles onto one set of nodes) or to the previous lap
#include "ScriptedDeciders.h"

#include <lodestone/graphslam/gso/CeresGSO.h>
#include <lodestone/graphslam/erd/CompositeERD.h>
#include <lodestone/graphslam/SlamEngine.h>
#include <SyntheticGraph.h>
#include <mrpt/obs/CObservationComment.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

using namespace lodestone;

int main(int argc, char** argv) {
    const std::string target = argc > 1 ? argv[1] : "";
    if (target != "first" && target != "previous") {
        std::fprintf(stderr, "usage: bench_graph_scaling first|previous [NODES ...]\n");
        return 2;
    }
    std::vector<int> sizes;
    for (int i = 2; i < argc; ++i) sizes.push_back(std::atoi(argv[i]));
    if (sizes.empty()) sizes = {1000, 5000, 10000};
    for (const int n : sizes) {
        graphslam::SyntheticGraph::Params p;
        p.side = 25.0;  // 400 nodes a lap
        const int perLap = static_cast<int>(4 * p.side / p.step);
        p.laps = std::max(2, (n + perLap - 1) / perLap);
        p.closureEvery = 8;
        p.closeToPreviousLap = target == "previous";
        auto s = graphslam::SyntheticGraph::make(p);
        std::vector<test::ScriptedNRD::Step> steps;
        for (std::size_t i = 0; i + 1 < s.truth.size() && static_cast<int>(i) + 1 < n; ++i) {
            steps.push_back({s.graph.edges.find({i, i + 1})->second, 0});
        }
        std::vector<graphslam::LoopClosure> closures;
        for (const auto& lc : s.closures) {
            if (static_cast<int>(lc.to) < n) closures.push_back(lc);
        }
        const double deadReckoning = graphslam::positionRmse(s.graph, s.truth);
        auto erd = std::make_unique<graphslam::CompositeERD>();
        erd->addChild(std::make_unique<test::ScriptedLoopCloser>(closures));
        graphslam::SlamEngine engine(std::make_unique<test::ScriptedNRD>(steps), std::move(erd),
                                     std::make_unique<graphslam::CeresGSO>());
        const auto tick = mrpt::obs::CObservationComment::Create();
        while (engine.process(tick)) {
        }
        const auto t0 = std::chrono::steady_clock::now();
        engine.finish();
        const double finalSolve =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const auto& gso = dynamic_cast<const graphslam::CeresGSO&>(engine.optimizer());
        std::vector<float> ms = engine.stats().nodeMs;
        std::string deciles;
        for (int d = 0; d < 10; ++d) {
            const std::size_t a = ms.size() * d / 10, b = ms.size() * (d + 1) / 10;
            double sum = 0;
            for (std::size_t i = a; i < b; ++i) sum += ms[i];
            char buf[16];
            std::snprintf(buf, sizeof buf, "%s%.2f", d ? " " : "", sum / std::max<std::size_t>(1, b - a));
            deciles += buf;
        }
        double mean = 0;
        for (float m : ms) mean += m;
        mean /= ms.size();
        std::sort(ms.begin(), ms.end());
        std::vector<mrpt::poses::CPose3D> truth(s.truth.begin(), s.truth.begin() + engine.graph().nodes.size());
        std::printf("| %s | %zu | %zu | %zu / %zu | %zu | %zu | %.2f / %.2f | %.2f | %.2f | %s | %.2f | %.3f (%.3f) |\n",
                    target.c_str(), engine.graph().nodes.size(), closures.size(), gso.stats().localSolves,
                    gso.stats().fullSolves, gso.stats().escalations, gso.stats().rejected,
                    gso.stats().localSeconds,
                    gso.stats().fullSeconds, mean, ms[ms.size() * 99 / 100],
                    deciles.c_str(), finalSolve, graphslam::positionRmse(engine.graph(), truth),
                    deadReckoning);
        std::fflush(stdout);
    }
    return 0;
}
