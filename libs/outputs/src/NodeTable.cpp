#include <lodestone/outputs/NodeTable.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace lodestone::outputs {

namespace {
constexpr const char* kHeader = "node,timestamp,segment,keyframe,engine_ms";
}

void writeNodeTable(const std::string& path, const std::vector<NodeRow>& rows) {
    std::ofstream out(path);
    if (!out) throw std::runtime_error(path + ": cannot write the node table");
    out << kHeader << "\n";
    char line[160];
    for (const auto& r : rows) {
        std::snprintf(line, sizeof line, "%llu,%.6f,%d,%d,%.4f\n",
                      static_cast<unsigned long long>(r.node), r.timestamp, r.segment,
                      r.keyframe ? 1 : 0, r.engineMs);
        out << line;
    }
    if (!out) throw std::runtime_error(path + ": write failed");
}

std::vector<NodeRow> readNodeTable(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open");
    std::string line;
    if (!std::getline(in, line) || line.rfind(kHeader, 0) != 0) {
        throw std::runtime_error(path + ": line 1: not a nodes.csv header");
    }
    std::vector<NodeRow> rows;
    for (std::size_t n = 2; std::getline(in, line); ++n) {
        if (line.empty()) continue;
        NodeRow r;
        int keyframe = 0;
        char ms[32] = {0};
        if (std::sscanf(line.c_str(), "%lld,%lf,%d,%d,%31s", &r.node, &r.timestamp, &r.segment,
                        &keyframe, ms) != 5) {
            throw std::runtime_error(path + ": line " + std::to_string(n) + ": expected 5 fields");
        }
        r.keyframe = keyframe != 0;
        r.engineMs = std::strtod(ms, nullptr);  // "nan" where the run did not time it
        rows.push_back(r);
    }
    return rows;
}

}  // namespace lodestone::outputs
