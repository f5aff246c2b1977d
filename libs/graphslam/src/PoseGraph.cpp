#include <lodestone/graphslam/PoseGraph.h>

namespace lodestone::graphslam {

bool eraseEdge(Graph& graph, TNodeID from, TNodeID to, const Constraint& c) {
    const auto range = graph.edges.equal_range({from, to});
    for (auto it = range.first; it != range.second; ++it) {
        if (it->second.mean == c.mean) {
            graph.edges.erase(it);
            return true;
        }
    }
    return false;
}

}  // namespace lodestone::graphslam
