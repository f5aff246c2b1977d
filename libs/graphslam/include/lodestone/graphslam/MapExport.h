#pragma once

#include <lodestone/graphslam/NodeStore.h>

#include <string>
#include <vector>

namespace lodestone::graphslam {

/** Writes the keyframe clouds, each moved by its node's (optimized) pose, as one coloured
 * binary PLY point cloud (x y z float, red green blue uchar). Returns the number of points.
 * Throws std::runtime_error naming `path` if it cannot be written. */
std::size_t writeMapPly(const std::string& path, const Graph& graph, const NodeStore& nodes);

/** Writes every node as a TUM trajectory line (its record's timestamp, its pose). */
void writeNodeTrajectory(const std::string& path, const Graph& graph, const NodeStore& nodes);

/** nodes.csv: per node its time, segment (one more after each kidnap), keyframe flag and the
 * engine time spent up to its registration [ms] (`engineMs`: SlamEngine::Stats::nodeMs, one per
 * node in ID order; NaN where missing). */
void writeNodeTable(const std::string& path, const NodeStore& nodes,
                    const std::vector<float>& engineMs);

}  // namespace lodestone::graphslam
