#include <lodestone/graphslam/ClosureLog.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace lodestone::graphslam {

namespace {
bool inGraph(const Graph& graph, const LoopClosure& lc) {
    const auto range = graph.edges.equal_range({lc.from, lc.to});
    for (auto it = range.first; it != range.second; ++it) {
        if (it->second.mean == lc.constraint.mean) return true;
    }
    return false;
}
}  // namespace

void writeClosureLog(const std::string& path, const SlamEngine& engine) {
    std::ofstream out(path);
    if (!out) throw std::runtime_error(path + ": cannot write the closure log");
    out << "from_node,to_node,from_time,to_time,source,match_id,score,strong,hypothesis,kept,"
           "x,y,z,yaw,pitch,roll\n";
    const auto& nodes = engine.nodes();
    char line[512];
    for (const auto& p : engine.proposals()) {
        const auto& lc = p.closure;
        const auto& m = lc.constraint.mean;
        std::snprintf(line, sizeof line,
                      "%llu,%llu,%.6f,%.6f,%s,%zu,%.6g,%d,%d,%d,%.6f,%.6f,%.6f,%.8f,%.8f,%.8f\n",
                      static_cast<unsigned long long>(lc.from),
                      static_cast<unsigned long long>(lc.to), nodes.at(lc.from).timestamp,
                      nodes.at(lc.to).timestamp, lc.source.c_str(), lc.matchId, lc.score,
                      lc.strong ? 1 : 0, p.hypothesis ? 1 : 0, inGraph(engine.graph(), lc) ? 1 : 0,
                      m.x(), m.y(), m.z(), m.yaw(), m.pitch(), m.roll());
        out << line;
    }
    if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace lodestone::graphslam
