#pragma once

#include <lodestone/graphslam/AttitudePrior.h>
#include <lodestone/graphslam/SlamComponent.h>
#include <mrpt/graphslam/interfaces/CGraphSlamOptimizer.h>

#include <set>
#include <vector>

namespace lodestone::graphslam {

/** Base of Lodestone's graph optimizers: MRPT's CGraphSlamOptimizer plus the explicit
 * loop-closure signal and an end-of-run solve. The optimizer owns the record of every loop
 * closure it was given, including those it later rejected. */
class GraphOptimizer : public mrpt::graphslam::optimizers::CGraphSlamOptimizer<Graph>,
                       public SlamComponent {
  public:
    void loadParams(const std::string& source_fname) override;
    /** Loop closures just added to the graph; the next updateState() decides how to solve. */
    virtual void addLoopClosures(const std::vector<LoopClosure>& closures) = 0;
    /** Closures that join a just-relocated group to the map: only the nodes in `movable` (the
     * moved group) may follow them now, so a relocation never moves the map; later full
     * solves treat them as any closure. The default treats them as any closure at once. */
    virtual void addRelocationClosures(const std::vector<LoopClosure>& closures,
                                       const std::set<TNodeID>& /*movable*/) {
        addLoopClosures(closures);
    }
    /** Nodes with an ID below `count` never move again (a map loaded to localize in). The
     * default refuses: an optimizer that cannot hold nodes fixed cannot localize. */
    virtual void holdFixed(TNodeID count);
    /** The graph starts with a loaded map's `count` nodes, solved when the map was saved:
     * what the optimizer counts as solved already (the default: nothing to count). */
    virtual void adoptMap(TNodeID /*count*/) {}
    /** A node's measured up (an accelerometer's): a prior on its roll and pitch in the solves
     * that follow. The default ignores it (an optimizer without roll and pitch). */
    virtual void addAttitudePrior(TNodeID /*id*/, const AttitudePrior& /*prior*/) {}
    /** The odometry edge from -> to as the wheels measured it: its (x, y, yaw) by the wheels'
     * (left, right) scale errors (WheelScale). The default ignores it (scales not estimated). */
    virtual void addWheelScaleJacobian(TNodeID /*from*/, TNodeID /*to*/,
                                       const Eigen::Matrix<double, 3, 2>& /*jacobian*/) {}
    /** Writes into `graph` (a copy of the one solved) the odometry edges as the solves used
     * them: corrected by what was estimated about the odometry (the wheels' scales), so a graph
     * or map written out holds the shape it was solved into. The default changes nothing. */
    virtual void calibrateEdges(Graph& /*graph*/) const {}
    /** Nodes solved in SE(3) (6 dof) rather than x, y, yaw: the relocalizer's space. */
    virtual bool spatial() const { return false; }
    /** Solves everything the run still needs (at the end of the data). */
    virtual void finish() = 0;
    /** Re-solves the whole graph now (e.g. after a kidnapped segment was re-anchored). */
    void optimizeGraph() override = 0;
    const std::vector<LoopClosure>& loopClosures() const { return closures_; }

  protected:
    std::vector<LoopClosure> closures_;
};

}  // namespace lodestone::graphslam
