#pragma once

#include <lodestone/graphslam/PoseGraph.h>
#include <lodestone/graphslam/gso/PoseGraphSolver.h>

#include <future>
#include <optional>
#include <vector>

namespace lodestone::graphslam {

/** A full solve of a snapshot of the graph on a second thread (as ORB-SLAM's loop-closing
 * thread), so that no frame waits for it, merged back into the live graph at a node count fixed
 * when it starts: results do not depend on how fast the thread runs (if the solve is not done
 * when the graph reaches that count, the frame loop waits for it there).
 *
 * Merging: the snapshot's nodes take their solved poses; nodes added since move rigidly with
 * the snapshot's last node (the odometry chain continues from where the solve put it); closures
 * the solve rejected are marked rejected in the live list and their edges erased. Closures
 * added since are not in the solve: the caller re-applies them (CeresGSO solves locally around
 * them). */
class BackgroundSolve {
  public:
    /** `attitude`: the nodes' measured ups; `wheels`: the odometry edges' wheel-scale
     * Jacobians (both copied; nullptr: none). */
    BackgroundSolve(const PoseGraphSolver::Options& options, const Graph& graph,
                    const std::vector<LoopClosure>& closures, std::size_t mergeAtNodes,
                    const AttitudePriors* attitude = nullptr, const WheelScale* wheels = nullptr);
    ~BackgroundSolve();
    BackgroundSolve(const BackgroundSolve&) = delete;
    BackgroundSolve& operator=(const BackgroundSolve&) = delete;

    std::size_t launchedAtNodes() const { return launched_at_; }
    std::size_t mergeAtNodes() const { return merge_at_; }
    std::size_t closuresAtLaunch() const { return closures_at_launch_; }

    /** Waits for the solve (`waitedSeconds`: how long), then merges it (the map's up it
     * solved into `attitude`, the wheels' scales into `wheels`); its report. */
    PoseGraphSolver::Report mergeInto(Graph& graph, std::vector<LoopClosure>& closures,
                                      double* waitedSeconds = nullptr,
                                      AttitudePriors* attitude = nullptr,
                                      WheelScale* wheels = nullptr);

  private:
    struct Outcome {
        Graph solved;
        std::vector<LoopClosure> closures;
        PoseGraphSolver::Report report;
        std::optional<AttitudePriors> attitude;
        std::optional<WheelScale> wheels;
    };
    std::size_t launched_at_, merge_at_, closures_at_launch_;
    TNodeID last_{0};  // the snapshot's last node
    std::future<Outcome> outcome_;
};

}  // namespace lodestone::graphslam
