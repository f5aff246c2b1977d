#pragma once

#include <lodestone/graphslam/SlamEngine.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/outputs/ClosureTable.h>
#include <lodestone/outputs/NodeTable.h>

#include <string>
#include <vector>

namespace lodestone::slamapp {

/** Writes the keyframe clouds, each moved by its node's (optimized) pose, as one coloured
 * binary PLY point cloud (x y z float, red green blue uchar). Returns the number of points.
 * Throws std::runtime_error naming `path` if it cannot be written. */
std::size_t writeMapPly(const std::string& path, const graphslam::Graph& graph,
                        const graphslam::NodeStore& nodes);

/** Every node of the graph, in ID order: its record's timestamp, its (optimized) pose. */
std::vector<io::TumPose> nodeTrajectory(const graphslam::Graph& graph,
                                        const graphslam::NodeStore& nodes);

/** Writes a trajectory as TUM lines (`.partial` until complete). */
void writeTrajectory(const std::string& path, const std::vector<io::TumPose>& trajectory);

/** Every loop closure the edge decider proposed (SlamEngine::proposals), for closures.csv: the
 * nodes' data timestamps, `hypothesis` when it joined two groups (after a kidnap), `kept` when
 * the final graph holds it as an edge (not rejected by the relocalizer or the optimizer). */
std::vector<outputs::ClosureRow> closureRows(const graphslam::SlamEngine& engine);

/** Per node its time, segment, keyframe flag and the engine time spent up to its registration
 * [ms] (`engineMs`: SlamEngine::Stats::nodeMs, one per node the run made, in ID order from
 * `firstTimed` - after a loaded map's nodes; NaN where missing). */
std::vector<outputs::NodeRow> nodeRows(const graphslam::NodeStore& nodes,
                                       const std::vector<float>& engineMs,
                                       graphslam::TNodeID firstTimed = 0);

}  // namespace lodestone::slamapp
