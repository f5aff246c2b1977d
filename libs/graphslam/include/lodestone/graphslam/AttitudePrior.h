#pragma once

#include <lodestone/graphslam/PoseGraph.h>

#include <Eigen/Core>
#include <map>

namespace lodestone::graphslam {

/** Which way is up at a node, measured (an IMU's accelerometer: odometry::GravityEstimator) or
 * the carrier's (a camera held level): an absolute constraint on the node's roll and pitch,
 * which relative edges only chain - and their errors add up, a camera's visual odometry tilting
 * its map by a degree or two a lap. With `heightSigma`, also the node's height along the map's
 * up: `height` above the level AttitudePriors::mapHeight marks - the floor a node's depth saw
 * (LevelFloor), or with `height` 0 the carrier's common height on one floor - whose height
 * relative edges chain just as loosely. */
struct AttitudePrior {
    Eigen::Vector3d up{0, 0, 1};  ///< the world's up in the node's (robot) frame, unit
    double sigma{0};              ///< per axis [rad] (0: no prior on the up)
    double heightSigma{0};        ///< [m] of `height` (0: no height)
    double height{0};             ///< [m] the node's height above mapHeight's level
};

/** The priors of a graph's nodes and the map frame's up they share: the map frame is where the
 * run started, which need not have been level, so its up is solved with them (by full solves;
 * a local solve holds it) - and with it the carrier's height along it, where nodes hold one. */
struct AttitudePriors {
    std::map<TNodeID, AttitudePrior> nodes;
    Eigen::Vector3d mapUp{0, 0, 1};
    /** [m] along mapUp in the map frame: the floor's (or the carrier's common height), which
     * each node's `height` is above. One graph holds one kind. */
    double mapHeight{0};
};

}  // namespace lodestone::graphslam
