#pragma once

#include <lodestone/graphslam/PoseGraph.h>

#include <opencv2/core.hpp>
#include <vector>

namespace lodestone::slamapp {

/** The pose graph seen from above, equal axes: the node chain (blue), accepted loop closures
 * (green) and those the optimizer rejected (red, drawn at the nodes' final poses). */
cv::Mat3b plotGraph(const graphslam::Graph& graph,
                    const std::vector<graphslam::LoopClosure>& closures, int size = 900);

}  // namespace lodestone::slamapp
