#pragma once

#include <lodestone/graphslam/SlamEngine.h>

#include <string>

namespace lodestone::graphslam {

/** Writes every loop closure the edge decider proposed (SlamEngine::proposals) as CSV, a line
 * each, so a benchmark can judge each matcher against the ground truth (lodestone-eval
 * closures):
 *
 *   from_node,to_node,from_time,to_time,source,match_id,score,strong,hypothesis,kept,
 *   x,y,z,yaw,pitch,roll
 *
 * times [s] are the nodes' data timestamps; `hypothesis` 1 when it joined two groups (after a
 * kidnap); `kept` 1 when the final graph holds it as an edge (not rejected by the relocalizer
 * or the optimizer); x..roll the measured pose of `to` in the frame of `from` [m, rad].
 * Throws std::runtime_error naming `path` if it cannot be written. */
void writeClosureLog(const std::string& path, const SlamEngine& engine);

}  // namespace lodestone::graphslam
