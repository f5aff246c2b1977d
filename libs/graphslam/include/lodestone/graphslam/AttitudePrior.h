#pragma once

#include <lodestone/graphslam/PoseGraph.h>

#include <Eigen/Core>
#include <map>

namespace lodestone::graphslam {

/** Which way is up at a node, measured (an IMU's accelerometer: odometry::GravityEstimator) or
 * the carrier's (a camera held level): an absolute constraint on the node's roll and pitch,
 * which relative edges only chain - and their errors add up, a camera's visual odometry tilting
 * its map by a degree or two a lap. With `heightSigma`, also the node's height along the map's
 * up: a carrier on one floor, whose height relative edges chain just as loosely. */
struct AttitudePrior {
    Eigen::Vector3d up{0, 0, 1};  ///< the world's up in the node's (robot) frame, unit
    double sigma{0};              ///< per axis [rad] (0: no prior on the up)
    double heightSigma{0};        ///< [m] about the carriers' common height (0: none)
};

/** The priors of a graph's nodes and the map frame's up they share: the map frame is where the
 * run started, which need not have been level, so its up is solved with them (by full solves;
 * a local solve holds it) - and with it the carrier's height along it, where nodes hold one. */
struct AttitudePriors {
    std::map<TNodeID, AttitudePrior> nodes;
    Eigen::Vector3d mapUp{0, 0, 1};
    double mapHeight{0};  ///< [m] the carrier's height along mapUp in the map frame
};

}  // namespace lodestone::graphslam
