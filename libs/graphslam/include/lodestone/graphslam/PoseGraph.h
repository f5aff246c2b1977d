#pragma once

#include <mrpt/graphs/CNetworkOfPoses.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <string>

namespace lodestone::graphslam {

/** The graph every Lodestone decider works on: MRPT's 3D network of poses with information
 * matrices (MRPT order x, y, z, yaw, pitch, roll). Ground robots keep z, pitch and roll at zero
 * and the optimizer may solve it on SE(2) (see PoseGraphSolver). */
using Graph = mrpt::graphs::CNetworkOfPoses3DInf;
using TNodeID = mrpt::graphs::TNodeID;
using Constraint = Graph::constraint_t;  // mrpt::poses::CPose3DPDFGaussianInf

/** A loop-closure edge and what became of it. The engine keeps one per closure an edge decider
 * proposed; the optimizer may later reject it (then it is gone from the graph). */
struct LoopClosure {
    TNodeID from{0}, to{0};
    Constraint constraint;
    std::string source;       ///< the matcher that proposed it (its class name)
    /** Closures from one match event of a matcher share it (e.g. the edges of one magnetic
     * alignment): they are not independent evidence of a relocation. */
    std::size_t matchId{0};
    /** The matcher judged its evidence strong enough to relocate on its own (its threshold). */
    bool strong{false};
    /** The matcher's own measure of its evidence, higher is stronger (OrbSubmapERD: RANSAC
     * inliers; MagneticGpERD: minus the alignment's normalized RMS residual). Benchmarks sweep
     * it to find each matcher's recall at 100 % precision. */
    double score{0};
    bool rejected{false};     ///< removed by the optimizer
    double rejectionChi2{0};  ///< its squared Mahalanobis residual when removed
};

/** A planar motion with its covariance as a graph edge: the x, y, yaw information from the
 * covariance (floored so a zero-motion, zero-covariance step stays invertible), z, pitch and roll
 * held by a stiff `planarStiffness` information (the robot stays on the floor). */
Constraint planarConstraint(const mrpt::poses::CPosePDFGaussian& motion);
constexpr double kPlanarStiffness = 1e6;  ///< information of z [1/m^2], pitch and roll [1/rad^2]

/** Removes the edge from->to whose mean is `c.mean` (there may be several between two nodes).
 * Returns false if there is none. */
bool eraseEdge(Graph& graph, TNodeID from, TNodeID to, const Constraint& c);
/** The odometry edge that brought node `id` (from id - 1): its length on the floor [m] and its
 * covariance's x and y variances summed [m^2] and yaw variance [rad^2]; zeros for the root or
 * where the graph has no such edge. */
struct OdometryStep {
    double length{0}, varianceXY{0}, varianceYaw{0};
};
OdometryStep odometryStepInto(const Graph& graph, TNodeID id);
/** Whether the graph holds the edge from->to whose mean is `c.mean`. */
bool hasEdge(const Graph& graph, TNodeID from, TNodeID to, const Constraint& c);

}  // namespace lodestone::graphslam
