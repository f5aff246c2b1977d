#include <lodestone/graphslam/MapExport.h>
#include <lodestone/io/TumTrajectory.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace lodestone::graphslam {

std::size_t writeMapPly(const std::string& path, const Graph& graph, const NodeStore& nodes) {
    std::size_t count = 0;
    for (TNodeID id = 0; id < nodes.size(); ++id) {
        const auto& r = nodes.at(id);
        if (r.cloud && graph.nodes.count(id)) count += r.cloud->points.size();
    }
    std::ofstream out(path, std::ios::binary);
    if (!out) throw std::runtime_error(path + ": cannot write the map");
    out << "ply\nformat binary_little_endian 1.0\ncomment Lodestone keyframe map\n"
        << "element vertex " << count << "\n"
        << "property float x\nproperty float y\nproperty float z\n"
        << "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
    for (TNodeID id = 0; id < nodes.size(); ++id) {
        const auto& r = nodes.at(id);
        if (!r.cloud || !graph.nodes.count(id)) continue;
        const mrpt::poses::CPose3D& pose = graph.nodes.at(id);
        for (const auto& p : r.cloud->points) {
            double gx, gy, gz;
            pose.composePoint(p.x, p.y, p.z, gx, gy, gz);
            const float xyz[3] = {static_cast<float>(gx), static_cast<float>(gy),
                                  static_cast<float>(gz)};
            out.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
            const std::uint8_t rgb[3] = {p.r, p.g, p.b};
            out.write(reinterpret_cast<const char*>(rgb), sizeof rgb);
        }
    }
    if (!out) throw std::runtime_error(path + ": write failed");
    return count;
}

void writeNodeTrajectory(const std::string& path, const Graph& graph, const NodeStore& nodes) {
    io::TumTrajectoryWriter w(path);
    for (TNodeID id = 0; id < nodes.size(); ++id) {
        if (graph.nodes.count(id)) w.write(nodes.at(id).timestamp, graph.nodes.at(id));
    }
    w.close();
}

void writeNodeTable(const std::string& path, const NodeStore& nodes,
                    const std::vector<float>& engineMs) {
    std::ofstream out(path);
    if (!out) throw std::runtime_error(path + ": cannot write the node table");
    out << "node,timestamp,segment,keyframe,engine_ms\n";
    char line[160];
    for (TNodeID id = 0; id < nodes.size(); ++id) {
        const auto& r = nodes.at(id);
        const double ms = id < engineMs.size() ? engineMs[id] : std::nan("");
        std::snprintf(line, sizeof line, "%llu,%.6f,%d,%d,%.4f\n",
                      static_cast<unsigned long long>(id), r.timestamp, r.segment,
                      r.keyframe ? 1 : 0, ms);
        out << line;
    }
    if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace lodestone::graphslam
