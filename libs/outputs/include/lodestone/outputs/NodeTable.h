#pragma once

#include <string>
#include <vector>

namespace lodestone::outputs {

/** One line of nodes.csv. */
struct NodeRow {
    long long node{0};
    double timestamp{0};
    int segment{0};        ///< one more after each kidnap
    bool keyframe{false};
    double engineMs{0};    ///< the engine's time for the node; NaN where it was not timed
};

/** Writes nodes.csv (a header, then a line per node). Throws naming the file on failure. */
void writeNodeTable(const std::string& path, const std::vector<NodeRow>& rows);

/** Reads nodes.csv; throws std::runtime_error naming the file and line when malformed. */
std::vector<NodeRow> readNodeTable(const std::string& path);

}  // namespace lodestone::outputs
