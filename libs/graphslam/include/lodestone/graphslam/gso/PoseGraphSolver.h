#pragma once

#include <lodestone/graphslam/AttitudePrior.h>
#include <lodestone/graphslam/PoseGraph.h>
#include <lodestone/graphslam/WheelScale.h>

#include <set>
#include <string>
#include <vector>

namespace lodestone::graphslam {

/** Non-linear least squares over a pose graph with Ceres (sparse Cholesky, Levenberg-Marquardt):
 * every edge contributes its relative-pose error whitened by the square root of its information
 * matrix; loop-closure edges go through a robust loss so one wrong closure cannot drag the graph
 * far before it is found and removed.
 *
 * Rejection: after a robust solve, the loop closure with the largest squared Mahalanobis
 * residual is removed from the graph if that residual exceeds `rejectionChi2` (a chi-square
 * quantile for 3 or 6 degrees of freedom), and the graph is solved again; repeated until every
 * remaining closure agrees. Odometry edges are never removed.
 *
 * Two parameterizations: `planar` (x, y, yaw per node; z, pitch and roll kept as they are and
 * only the x, y, yaw block of each information matrix used) for ground robots, and full SE(3)
 * (translation + unit quaternion). */
/** chi-square quantiles at 99.9 % for 3 (planar) and 6 (SE(3)) degrees of freedom. */
constexpr double kChi2Planar999 = 16.266;
constexpr double kChi2Se3999 = 22.458;

class PoseGraphSolver {
  public:
    struct Options {
        bool planar{true};
        std::string robustLoss{"cauchy"};  ///< none | huber | cauchy (on loop closures only)
        double robustScale{1.0};           ///< [sigmas] where the loss leaves quadratic
        double rejectionChi2{kChi2Planar999};  ///< kChi2Se3999 for SE(3)
        int maxIterations{100};
        double functionTolerance{1e-9};  ///< relative cost change that ends a solve
        int maxRejectionsPerSolve{10};
        /** Nodes with a lower ID never move (a loaded map, localize mode); 0: none. */
        TNodeID fixedBelow{0};
    };

    struct Report {
        std::size_t variableNodes{0}, fixedNodes{0}, edges{0};
        int iterations{0}, solves{0};
        double initialCost{0}, finalCost{0};
        double seconds{0};
        bool converged{true};
        std::vector<LoopClosure> rejected;  ///< removed from the graph by this call
    };

    explicit PoseGraphSolver(Options options);

    /** Optimizes `graph` in place. `loopClosures`: the closures currently in the graph (robust
     * loss, candidates for removal); rejected ones are marked there and erased from the graph.
     * `window`: the nodes to move (all edges touching one of them take part; their other ends
     * stay fixed); empty = every node. The graph root is always held fixed (the gauge).
     * `reject` false: solve only, never remove a closure (a local window cannot judge a
     * closure whose correction reaches beyond it).
     * `attitude` (SE(3) only): the nodes' measured up directions, each a prior on its node's
     * roll and pitch; a full solve of a graph with no fixed map also solves the map's up
     * (written back), other solves hold it.
     * `wheels`: the odometry edges' scale Jacobians; each such edge is corrected by the wheels'
     * scale errors, which a full solve estimates (written back) and other solves hold. */
    Report solve(Graph& graph, std::vector<LoopClosure>& loopClosures,
                 const std::set<TNodeID>& window = {}, bool reject = true,
                 AttitudePriors* attitude = nullptr, WheelScale* wheels = nullptr) const;

    /** Squared Mahalanobis residual of one edge at the graph's current node poses, in the
     * solver's parameterization. */
    double squaredResidual(const Graph& graph, TNodeID from, TNodeID to,
                           const Constraint& c) const;

    const Options& options() const { return options_; }

  private:
    Options options_;
};

}  // namespace lodestone::graphslam
