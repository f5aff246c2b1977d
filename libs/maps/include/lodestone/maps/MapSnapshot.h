#pragma once

#include <lodestone/graphslam/NodeStore.h>
#include <lodestone/maps/SavedMap.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace lodestone::maps {

/** The map a run holds now: its graph and node records (every node of session 0), the INI text
 * that shaped them and the deciders its [graphslam] section names. */
SavedMap mapOf(const graphslam::Graph& graph, const graphslam::NodeStore& nodes,
               const std::string& configText, const std::string& createdBy);

/** The same for a run that extended a loaded map: only the nodes `keep` says (the map's and
 * those of the run that joined it), numbered 0, 1, ... in ID order, with the edges between
 * them; `sessions[id]` each node's session. */
SavedMap mapOf(const graphslam::Graph& graph, const graphslam::NodeStore& nodes,
               const std::vector<std::uint32_t>& sessions,
               const std::function<bool(graphslam::TNodeID)>& keep, const std::string& configText,
               const std::string& createdBy);

}  // namespace lodestone::maps
