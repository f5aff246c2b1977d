#pragma once

#include <lodestone/graphslam/NodeStore.h>
#include <lodestone/maps/SavedMap.h>

#include <string>

namespace lodestone::maps {

/** The map a run holds now: its graph and node records (every node of session 0), the INI text
 * that shaped them and the deciders its [graphslam] section names. */
SavedMap mapOf(const graphslam::Graph& graph, const graphslam::NodeStore& nodes,
               const std::string& configText, const std::string& createdBy);

}  // namespace lodestone::maps
