#pragma once

#include <lodestone/graphslam/PoseGraph.h>
#include <lodestone/graphslam/WheelScale.h>

#include <Eigen/Core>
#include <vector>

namespace lodestone::graphslam {

/** Two laps of a 6 x 3 m rectangle driven by wheels whose true travels are their measured
 * ones times 1 + scale (left, right): the odometry edges from the measured travels (0.1 m a
 * node, corners turned on the spot), with their scale Jacobians, and one closure a lap where
 * the robot passes its start again (the truth, 1 cm / 0.5 deg). */
struct ScaledLoop {
    Graph graph, truth;
    std::vector<LoopClosure> closures;
    WheelScale wheels;
};

ScaledLoop scaledLoop(const Eigen::Vector2d& scale);

/** The largest horizontal distance of a node of `g` from its place in `truth`. */
double worstError(const Graph& g, const Graph& truth);

}  // namespace lodestone::graphslam
