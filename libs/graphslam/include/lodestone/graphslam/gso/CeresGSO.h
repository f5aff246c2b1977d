#pragma once

#include <lodestone/graphslam/GraphOptimizer.h>
#include <lodestone/graphslam/gso/BackgroundSolve.h>
#include <lodestone/graphslam/gso/PoseGraphSolver.h>

namespace lodestone::graphslam {

/** The pose-graph optimizer: PoseGraphSolver (Ceres, sparse, robust loss on loop closures,
 * removal of closures the optimized graph cannot agree with) on a schedule that keeps the
 * per-node cost flat:
 *  - after new loop closures, a local solve over the nodes within `local_window` node IDs of
 *    their ends (the rest held fixed), so the current estimate follows at once; if a new
 *    closure still disagrees after it (beyond the rejection gate), a full solve instead, which
 *    alone may reject closures;
 *  - a full solve when closures arrived and the graph grew by `full_solve_growth` since the last
 *    full solve (a geometric schedule: their total cost stays proportional to the run), and
 *    always at the end.
 * INI [CeresGSO]: mode = planar | se3, robust_loss, robust_scale, rejection_chi2 (0: the
 * chi-square 99.9 % quantile for the mode's degrees of freedom), max_iterations, local_window,
 * full_solve_growth, wheel_scale_sigma (> 0: the wheels' scale errors estimated by full
 * solves, this prior sigma each; WheelScale). */
class CeresGSO : public GraphOptimizer {
  public:
    struct Params {
        PoseGraphSolver::Options solver;
        int localWindow{40};          ///< [node IDs] either side of a closure's ends
        double fullSolveGrowth{1.0};  ///< relative graph growth between full solves
        /** A growth-triggered full solve runs on a second thread on a snapshot and is merged
         * this many nodes later (BackgroundSolve); 0: it runs in the frame loop. Escalations
         * and the last solve stay in the frame loop. */
        int backgroundMergeNodes{0};
        /** Prior sigma of each wheel's scale error [fraction]; 0: not estimated. */
        double wheelScaleSigma{0.01};
    };

    CeresGSO();
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    const Params& params() const { return params_; }

    bool updateState(mrpt::obs::CActionCollection::Ptr action,
                     mrpt::obs::CSensoryFrame::Ptr observations,
                     mrpt::obs::CObservation::Ptr observation) override;
    void addLoopClosures(const std::vector<LoopClosure>& closures) override;
    /** Solves the moved group alone against them at once (the map held fixed). */
    void addRelocationClosures(const std::vector<LoopClosure>& closures,
                               const std::set<TNodeID>& movable) override;
    void optimizeGraph() override;
    void finish() override;
    bool justFullyOptimizedGraph() const override { return just_full_; }
    bool spatial() const override { return !params_.solver.planar; }
    /** Kept in SE(3) mode (planar solves have no roll or pitch to hold). */
    void addAttitudePrior(TNodeID id, const AttitudePrior& prior) override;
    const AttitudePriors& attitudePriors() const { return attitude_; }
    /** Kept when wheel_scale_sigma > 0. */
    void addWheelScaleJacobian(TNodeID from, TNodeID to,
                               const Eigen::Matrix<double, 3, 2>& jacobian) override;
    const WheelScale& wheelScale() const { return wheels_; }
    void calibrateEdges(Graph& graph) const override;
    void holdFixed(TNodeID count) override;
    /** A loaded map is the last full solve: the graph's growth (full_solve_growth) counts from
     * it, so the first closure of a run in a large map does not solve the whole map again. */
    void adoptMap(TNodeID count) override;
    JsonObject describe() const override;

    /** Totals over the run. */
    struct Stats {
        std::size_t localSolves{0}, fullSolves{0}, iterations{0};
        double localSeconds{0}, fullSeconds{0};
        std::size_t rejected{0};
        std::size_t escalations{0};  ///< local solves a new closure still disagreed with
        std::size_t backgroundSolves{0}, backgroundDiscarded{0};
        double backgroundWaitSeconds{0};  ///< the frame loop waiting at a merge
    };
    const Stats& stats() const { return stats_; }

  private:
    void absorb(const PoseGraphSolver::Report& r, bool full);
    /** Merges the background solve if the graph has reached its node count. */
    void mergeBackgroundIfDue();
    /** A solve of the live graph supersedes one running on an older snapshot. */
    void discardBackground();

    /** The priors for a solve: none while there are none. */
    AttitudePriors* priors() { return attitude_.nodes.empty() ? nullptr : &attitude_; }
    /** The wheels' scales for a solve: none while they are not estimated. */
    WheelScale* wheels() { return wheels_.active() ? &wheels_ : nullptr; }

    Params params_;
    AttitudePriors attitude_;
    bool map_height_set_{false};  // (by the first prior with a height)
    WheelScale wheels_;
    std::unique_ptr<PoseGraphSolver> solver_;
    std::unique_ptr<BackgroundSolve> background_;
    std::vector<std::pair<TNodeID, TNodeID>> pending_;  // ends of closures not solved yet
    std::size_t nodes_at_last_full_{0};
    bool closures_since_full_{false};
    bool just_full_{false};
    Stats stats_;
};

}  // namespace lodestone::graphslam
