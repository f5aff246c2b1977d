#include <lodestone/maps/MapSnapshot.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <map>

namespace lodestone::maps {

namespace {

void describeDeciders(SavedMap& map, const std::string& configText, const std::string& createdBy) {
    map.config = configText;
    const mrpt::config::CConfigFileMemory ini(configText);
    map.manifest.createdBy = createdBy;
    map.manifest.nodeDecider = ini.read_string_first_word("graphslam", "node_decider", "");
    map.manifest.edgeDecider = ini.read_string_first_word("graphslam", "edge_decider", "");
    map.manifest.optimizer = ini.read_string_first_word("graphslam", "optimizer", "");
}

}  // namespace

SavedMap mapOf(const graphslam::Graph& graph, const graphslam::NodeStore& nodes,
               const std::string& configText, const std::string& createdBy) {
    SavedMap map;
    map.graph = graph;
    map.nodes = nodes.records();
    for (auto& r : map.nodes) r.cloud.reset();  // (map.ply's; not a map's)
    map.sessions.assign(map.nodes.size(), 0);
    describeDeciders(map, configText, createdBy);
    return map;
}

SavedMap mapOf(const graphslam::Graph& graph, const graphslam::NodeStore& nodes,
               const std::vector<std::uint32_t>& sessions,
               const std::function<bool(graphslam::TNodeID)>& keep, const std::string& configText,
               const std::string& createdBy) {
    SavedMap map;
    std::map<graphslam::TNodeID, graphslam::TNodeID> renumbered;
    for (graphslam::TNodeID id = 0; id < nodes.size(); ++id) {
        if (!keep(id) || !graph.nodes.count(id)) continue;
        const auto to = static_cast<graphslam::TNodeID>(map.nodes.size());
        renumbered[id] = to;
        map.graph.nodes[to] = graph.nodes.at(id);
        map.nodes.push_back(nodes.at(id));
        map.nodes.back().cloud.reset();
        map.sessions.push_back(id < sessions.size() ? sessions[id] : 0);
    }
    for (const auto& [ends, edge] : graph.edges) {
        const auto a = renumbered.find(ends.first), b = renumbered.find(ends.second);
        if (a != renumbered.end() && b != renumbered.end())
            map.graph.insertEdge(a->second, b->second, edge);
    }
    map.graph.root = 0;
    describeDeciders(map, configText, createdBy);
    return map;
}

}  // namespace lodestone::maps
