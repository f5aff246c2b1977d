#pragma once

#include <lodestone/graphslam/PoseGraph.h>

#include <cstdint>
#include <vector>

namespace lodestone::graphslam {

/** A planar pose graph with known truth, for tests and benchmarks: a robot drives `laps` times
 * around a `side` x `side` square with a node every `step` metres; odometry edges carry
 * Gaussian noise drawn from exactly the covariance they claim, and every node of a later lap
 * within `closureEvery` nodes gets a loop closure to the same place on the first lap (noise drawn
 * from its claimed covariance as well; or to the previous lap, see Params). Node poses start at the odometry's dead reckoning. */
struct SyntheticGraph {
    struct Params {
        int laps{3};
        double side{8.0};           ///< [m]
        double step{0.25};          ///< [m] between nodes
        double odometrySigmaXY{0.01};    ///< [m] per edge
        double odometrySigmaYaw{0.004};  ///< [rad] per edge
        double closureSigmaXY{0.02};
        double closureSigmaYaw{0.005};
        int closureEvery{4};  ///< a closure on every n-th node of later laps (0: none)
        /** Closures go to the same place on the first lap (every revisit piles onto it), or
         * on the previous lap (each place keeps a bounded number of closures). */
        bool closeToPreviousLap{false};
        std::uint64_t seed{1};
    };

    Graph graph;                               ///< odometry edges only
    std::vector<mrpt::poses::CPose3D> truth;   ///< per node
    std::vector<LoopClosure> closures;         ///< not yet in `graph`
    std::size_t nodesPerLap{0};

    static SyntheticGraph make(const Params& p);
};

/** A planar information matrix (MRPT 6x6 order) with the given standard deviations for x, y
 * and yaw and very confident z, pitch, roll (the robot stays on the floor). */
mrpt::math::CMatrixDouble66 planarInformation(double sigmaXY, double sigmaYaw);

/** RMS of the position differences between graph nodes and `truth` after both are expressed
 * relative to node 0 (no other alignment). */
double positionRmse(const Graph& graph, const std::vector<mrpt::poses::CPose3D>& truth);

}  // namespace lodestone::graphslam
