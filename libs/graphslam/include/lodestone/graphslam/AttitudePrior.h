#pragma once

#include <lodestone/graphslam/PoseGraph.h>

#include <Eigen/Core>
#include <map>

namespace lodestone::graphslam {

/** Which way is up at a node, measured (an IMU's accelerometer: odometry::GravityEstimator):
 * an absolute constraint on the node's roll and pitch, which relative edges only chain - and
 * their errors add up, a camera's visual odometry tilting its map by a degree or two a lap. */
struct AttitudePrior {
    Eigen::Vector3d up{0, 0, 1};  ///< the world's up in the node's (robot) frame, unit
    double sigma{0};              ///< per axis [rad]
};

/** The priors of a graph's nodes and the map frame's up they share: the map frame is where the
 * run started, which need not have been level, so its up is solved with them (by full solves;
 * a local solve holds it). */
struct AttitudePriors {
    std::map<TNodeID, AttitudePrior> nodes;
    Eigen::Vector3d mapUp{0, 0, 1};
};

}  // namespace lodestone::graphslam
