#include <lodestone/maps/MapSummary.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace lodestone::maps {

MapSummary summarizeMap(const SavedMap& map, const std::string& dir) {
    MapSummary s;
    s.manifest = map.manifest;
    bool first = true;
    for (const auto& [id, pose] : map.graph.nodes) {
        s.minX = first ? pose.x() : std::min(s.minX, pose.x());
        s.maxX = first ? pose.x() : std::max(s.maxX, pose.x());
        s.minY = first ? pose.y() : std::min(s.minY, pose.y());
        s.maxY = first ? pose.y() : std::max(s.maxY, pose.y());
        first = false;
        if (id == 0 || id >= map.nodes.size()) continue;
        if (map.nodes[id].segment != map.nodes[id - 1].segment) continue;
        const auto before = map.graph.nodes.find(id - 1);
        if (before != map.graph.nodes.end())
            s.pathLength += std::hypot(pose.x() - before->second.x(), pose.y() - before->second.y());
    }
    for (const auto& r : map.nodes)
        if (r.features) s.features += r.features->size();
    if (!dir.empty()) {
        for (const auto& e : std::filesystem::directory_iterator(dir))
            if (e.is_regular_file()) s.bytesOnDisk += e.file_size();
    }
    std::istringstream config(map.config);
    for (std::string line; std::getline(config, line);) {
        const auto open = line.find_first_not_of(" \t");
        if (open == std::string::npos || line[open] != '[') continue;
        const auto close = line.find(']', open);
        if (close != std::string::npos) s.configSections.push_back(line.substr(open + 1, close - open - 1));
    }
    return s;
}

void printMapSummary(const MapSummary& s, std::ostream& out) {
    const auto& m = s.manifest;
    char line[256];
    out << "format " << m.formatVersion << ", made by " << m.createdBy << ", " << m.sessions
        << (m.sessions == 1 ? " session" : " sessions") << "\n";
    out << "nodes " << m.nodes << " in " << m.segments << (m.segments == 1 ? " segment" : " segments")
        << ", edges " << m.edges << ", keyframes " << m.keyframes << " (" << s.features
        << " ORB features), magnetometer readings " << m.magneticReadings << "\n";
    std::snprintf(line, sizeof line,
                  "extent x %.2f .. %.2f m, y %.2f .. %.2f m; path %.1f m\n", s.minX, s.maxX,
                  s.minY, s.maxY, s.pathLength);
    out << line;
    out << "magnetometers:";
    for (const auto& l : m.magnetometers) out << " " << l;
    out << (m.magnetometers.empty() ? " none\n" : "\n");
    out << "deciders: " << m.nodeDecider << ", " << m.edgeDecider << ", " << m.optimizer << "\n";
    out << "config sections:";
    for (const auto& c : s.configSections) out << " [" << c << "]";
    out << "\n";
    if (s.bytesOnDisk) {
        std::snprintf(line, sizeof line, "on disk %.1f kB, %.0f bytes a node\n",
                      double(s.bytesOnDisk) / 1e3,
                      m.nodes ? double(s.bytesOnDisk) / double(m.nodes) : 0.0);
        out << line;
    }
}

}  // namespace lodestone::maps
