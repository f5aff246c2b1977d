#include <lodestone/maps/MapSnapshot.h>
#include <mrpt/config/CConfigFileMemory.h>

namespace lodestone::maps {

SavedMap mapOf(const graphslam::Graph& graph, const graphslam::NodeStore& nodes,
               const std::string& configText, const std::string& createdBy) {
    SavedMap map;
    map.graph = graph;
    map.nodes = nodes.records();
    for (auto& r : map.nodes) r.cloud.reset();  // (map.ply's; not a map's)
    map.sessions.assign(map.nodes.size(), 0);
    map.config = configText;
    const mrpt::config::CConfigFileMemory ini(configText);
    map.manifest.createdBy = createdBy;
    map.manifest.nodeDecider = ini.read_string_first_word("graphslam", "node_decider", "");
    map.manifest.edgeDecider = ini.read_string_first_word("graphslam", "edge_decider", "");
    map.manifest.optimizer = ini.read_string_first_word("graphslam", "optimizer", "");
    return map;
}

}  // namespace lodestone::maps
