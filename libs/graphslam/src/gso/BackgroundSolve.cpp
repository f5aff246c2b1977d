#include <lodestone/graphslam/gso/BackgroundSolve.h>

#include <chrono>

namespace lodestone::graphslam {

BackgroundSolve::BackgroundSolve(const PoseGraphSolver::Options& options, const Graph& graph,
                                 const std::vector<LoopClosure>& closures, std::size_t mergeAtNodes,
                                 const AttitudePriors* attitude, const WheelScale* wheels)
    : launched_at_(graph.nodes.size()),
      merge_at_(mergeAtNodes),
      closures_at_launch_(closures.size()) {
    if (!graph.nodes.empty()) last_ = graph.nodes.rbegin()->first;
    // The snapshot is copied here, on the caller's thread; the worker owns its copy.
    std::optional<AttitudePriors> priors;
    if (attitude) priors = *attitude;
    std::optional<WheelScale> scales;
    if (wheels) scales = *wheels;
    outcome_ = std::async(std::launch::async, [options, snapshot = graph, list = closures,
                                               priors = std::move(priors),
                                               scales = std::move(scales)]() mutable {
        Outcome o;
        o.report = PoseGraphSolver(options).solve(snapshot, list, {}, true,
                                                  priors ? &*priors : nullptr,
                                                  scales ? &*scales : nullptr);
        o.attitude = std::move(priors);
        o.wheels = std::move(scales);
        o.solved = std::move(snapshot);
        o.closures = std::move(list);
        return o;
    });
}

BackgroundSolve::~BackgroundSolve() {
    if (outcome_.valid()) outcome_.wait();  // (a discarded solve still finishes first)
}

PoseGraphSolver::Report BackgroundSolve::mergeInto(Graph& graph, std::vector<LoopClosure>& closures,
                                                   double* waitedSeconds,
                                                   AttitudePriors* attitude,
                                                   WheelScale* wheels) {
    const auto t0 = std::chrono::steady_clock::now();
    Outcome o = outcome_.get();
    if (waitedSeconds) {
        *waitedSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    if (attitude && o.attitude) {
        attitude->mapUp = o.attitude->mapUp;
        attitude->mapHeight = o.attitude->mapHeight;
    }
    if (wheels && o.wheels) wheels->scale = o.wheels->scale;
    // Nodes added since the snapshot keep their pose relative to its last node.
    const mrpt::poses::CPose3D lastBefore = graph.nodes.at(last_);
    const mrpt::poses::CPose3D lastAfter = o.solved.nodes.at(last_);
    for (auto& [id, pose] : graph.nodes) {
        const auto solved = o.solved.nodes.find(id);
        pose = solved != o.solved.nodes.end() ? solved->second : lastAfter + (pose - lastBefore);
    }
    for (std::size_t k = 0; k < o.closures.size() && k < closures.size(); ++k) {
        const auto& s = o.closures[k];
        auto& live = closures[k];
        if (s.rejected && !live.rejected) {
            live.rejected = true;
            live.rejectionChi2 = s.rejectionChi2;
            eraseEdge(graph, live.from, live.to, live.constraint);
        }
    }
    return o.report;
}

}  // namespace lodestone::graphslam
