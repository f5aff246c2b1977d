// A map folder: manifest.ini, config.ini, graph.bin (the graph, MRPT's serialization: exact),
// graph.graph (the same graph as MRPT's text format, for its tools) and nodes.bin (a header, then
// one CMapNode per node through MRPT's versioned serialization).
#include <lodestone/config/IniSection.h>
#include <lodestone/maps/MapNode.h>
#include <lodestone/maps/SavedMap.h>
#include <lodestone/memguard/AllocationBudget.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/CFileInputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace lodestone::maps {

namespace fs = std::filesystem;

namespace {

constexpr const char* kNodesHeader = "lodestone map nodes";

// What reading a node (or the graph) may allocate (memguard::AllocationBudget): MRPT allocates
// what a size field says before it reads the data, so a damaged size would take gigabytes. The
// data must be in the file: a multiple of the bytes left in it, over a floor for bookkeeping.
constexpr std::uint64_t kAllocationFloor = 16ull << 20;
constexpr std::uint64_t kBytesPerStoredByte = 8;

std::uint64_t allocationLimit(std::uint64_t bytesLeft) {
    return kAllocationFloor + kBytesPerStoredByte * bytesLeft;
}

struct FileSpec {
    MapFile file;
    const char* name;
};
constexpr FileSpec kFiles[] = {{MapFile::Manifest, "manifest.ini"},
                               {MapFile::Config, "config.ini"},
                               {MapFile::Graph, "graph.bin"},
                               {MapFile::GraphText, "graph.graph"},
                               {MapFile::Nodes, "nodes.bin"}};

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw MapError(path + ": cannot be read (missing?)");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void writeText(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    if (!out.flush()) throw MapError(path + ": cannot be written");
}

/** An exception's message in one line: MRPT's "Message:" line where it has one. */
std::string briefly(const std::exception& e) {
    std::string what = e.what();
    const auto at = what.find("Message:");
    if (at != std::string::npos) what = what.substr(at + 8);
    what = what.substr(what.find_first_not_of(" \t") == std::string::npos
                           ? 0
                           : what.find_first_not_of(" \t"));
    return what.substr(0, std::min(what.find('\n'), std::size_t(200)));
}

MapManifest manifestOf(const SavedMap& map) {
    MapManifest m = map.manifest;
    m.formatVersion = kMapFormatVersion;
    m.nodes = map.nodes.size();
    m.edges = map.graph.edges.size();
    m.keyframes = 0;
    m.magneticReadings = 0;
    m.segments = 0;
    std::set<std::string> labels;
    for (const auto& r : map.nodes) {
        for (const auto& s : r.magnetic)
            if (!isMapLabel(s.sensorLabel))
                throw MapError("magnetometer label '" + s.sensorLabel +
                               "': a map holds labels of printable characters without spaces");
        m.keyframes += r.keyframe;
        m.magneticReadings += r.magnetic.size();
        m.segments = std::max(m.segments, r.segment + 1);
        for (const auto& s : r.magnetic) labels.insert(s.sensorLabel);
    }
    m.magnetometers.assign(labels.begin(), labels.end());
    m.sessions = 1;
    for (const auto s : map.sessions) m.sessions = std::max(m.sessions, s + 1);
    return m;
}

std::string manifestText(const MapManifest& m) {
    std::ostringstream s;
    s << "; A Lodestone map (lodestone-slam --map-out): what the other files hold, checked on load.\n"
      << "[map]\n"
      << "format_version    = " << m.formatVersion << "\n"
      << "created_by        = " << m.createdBy << "\n"
      << "sessions          = " << m.sessions << "\n"
      << "nodes             = " << m.nodes << "\n"
      << "edges             = " << m.edges << "\n"
      << "keyframes         = " << m.keyframes << "\n"
      << "segments          = " << m.segments << "\n"
      << "magnetic_readings = " << m.magneticReadings << "\n"
      << "magnetometers     =";
    for (const auto& l : m.magnetometers) s << " " << l;
    s << "\n"
      << "node_decider      = " << m.nodeDecider << "\n"
      << "edge_decider      = " << m.edgeDecider << "\n"
      << "optimizer         = " << m.optimizer << "\n";
    return s.str();
}

MapManifest parseManifest(const std::string& path) {
    const std::string text = readText(path);
    MapManifest m;
    try {
        // (MRPT's parser throws on what it cannot parse, e.g. an unclosed "$env{")
        mrpt::config::CConfigFileMemory ini(text);
        config::checkSections(ini, {"map"}, path);
        config::IniSection s(ini, "map", path);
        // (bounded before the cast: a double beyond the type's range is undefined behaviour)
        const auto count = [&](const char* key, double most = 1e15) {
            const double v = s.requireDouble(key);
            if (!(v >= 0 && v <= most) || v != std::floor(v)) s.fail(key, "must be a count");
            return static_cast<std::size_t>(v);
        };
        constexpr double kMostInt = 2147483647.0;
        m.formatVersion = static_cast<int>(count("format_version", kMostInt));
        if (m.formatVersion > kMapFormatVersion) {
            s.fail("format_version", "map format " + std::to_string(m.formatVersion) +
                                         " is newer than this build reads (" +
                                         std::to_string(kMapFormatVersion) + ")");
        }
        if (m.formatVersion < 1) s.fail("format_version", "must be >= 1");
        m.createdBy = s.getString("created_by", "");
        m.sessions = static_cast<std::uint32_t>(count("sessions", kMostInt));
        m.nodes = count("nodes");
        m.edges = count("edges");
        m.keyframes = count("keyframes");
        m.segments = static_cast<int>(count("segments", kMostInt));
        m.magneticReadings = count("magnetic_readings");
        std::istringstream labels(s.getString("magnetometers", ""));
        for (std::string l; labels >> l;) m.magnetometers.push_back(l);
        m.nodeDecider = s.requireString("node_decider");
        m.edgeDecider = s.requireString("edge_decider");
        m.optimizer = s.requireString("optimizer");
        s.finish();
    } catch (const config::ConfigError& e) {
        throw MapError(e.what());
    } catch (const std::exception& e) {
        throw MapError(path + ": not an INI file (" + briefly(e) + ")");
    }
    return m;
}

void registerMapClasses() {
    static const bool once = [] {
        mrpt::rtti::registerClass(CLASS_ID(CMapNode));
        return true;
    }();
    (void)once;
}

void writeNodes(const SavedMap& map, const std::string& path) {
    mrpt::io::CFileOutputStream stream;
    if (!stream.open(path)) throw MapError(path + ": cannot be written");
    auto out = mrpt::serialization::archiveFrom(stream);
    out << std::string(kNodesHeader) << static_cast<std::uint64_t>(map.nodes.size());
    for (std::size_t id = 0; id < map.nodes.size(); ++id) {
        CMapNode node;
        node.id = id;
        node.session = id < map.sessions.size() ? map.sessions[id] : 0;
        node.record = map.nodes[id];
        node.record.cloud.reset();
        out << node;
    }
}

void readNodes(const std::string& path, std::size_t expected, SavedMap& map) {
    registerMapClasses();
    mrpt::io::CFileInputStream stream;
    if (!stream.open(path)) throw MapError(path + ": cannot be read (missing?)");
    auto in = mrpt::serialization::archiveFrom(stream);
    std::size_t id = 0;
    try {
        std::string header;
        std::uint64_t count = 0;
        {
            memguard::AllocationBudget budget(allocationLimit(stream.getTotalBytesCount()));
            try {
                in >> header;
            } catch (...) {
                if (budget.exceeded()) throw MapError(path + ": not a Lodestone map's node file");
                throw;
            }
        }
        if (header != kNodesHeader) throw MapError(path + ": not a Lodestone map's node file");
        in >> count;
        if (count != expected) {
            throw MapError(path + ": holds " + std::to_string(count) + " nodes, the manifest " +
                           std::to_string(expected));
        }
        for (; id < count; ++id) {
            CMapNode node;
            {
                const std::uint64_t left = stream.getTotalBytesCount() - stream.getPosition();
                memguard::AllocationBudget budget(allocationLimit(left));
                try {
                    in >> node;
                } catch (...) {
                    if (budget.exceeded())
                        throw MapError(path + ": node " + std::to_string(id) +
                                       " is damaged (a size field asks for more than the " +
                                       std::to_string(left) + " bytes left can hold)");
                    throw;
                }
            }
            if (node.id != id) {
                throw MapError(path + ": node " + std::to_string(id) + " is stored as node " +
                               std::to_string(node.id));
            }
            map.nodes.push_back(std::move(node.record));
            map.sessions.push_back(node.session);
        }
    } catch (const MapError&) {
        throw;
    } catch (const std::exception& e) {
        throw MapError(path + ": node " + std::to_string(id) + " is damaged (" + briefly(e) + ")");
    }
    if (stream.getPosition() != stream.getTotalBytesCount())
        throw MapError(path + ": data after the last node");
}

}  // namespace

const char* fileName(MapFile file) {
    for (const auto& f : kFiles)
        if (f.file == file) return f.name;
    return "";
}

std::string pathIn(const std::string& dir, MapFile file) {
    return (fs::path(dir) / fileName(file)).string();
}

void writeMap(const SavedMap& map, const std::string& dir) {
    if (map.graph.nodes.size() != map.nodes.size())
        throw MapError(dir + ": the graph has " + std::to_string(map.graph.nodes.size()) +
                       " nodes, the records " + std::to_string(map.nodes.size()));
    const std::string partial = dir + ".partial";
    std::error_code ec;
    fs::remove_all(partial, ec);
    if (!fs::create_directories(partial, ec) && ec)
        throw MapError(partial + ": cannot be created (" + ec.message() + ")");
    writeText(pathIn(partial, MapFile::Manifest), manifestText(manifestOf(map)));
    writeText(pathIn(partial, MapFile::Config), map.config);
    {
        mrpt::io::CFileOutputStream stream;
        const auto path = pathIn(partial, MapFile::Graph);
        if (!stream.open(path)) throw MapError(path + ": cannot be written");
        auto archive = mrpt::serialization::archiveFrom(stream);
        static_cast<mrpt::serialization::CArchive&>(archive) << map.graph;
    }
    map.graph.saveToTextFile(pathIn(partial, MapFile::GraphText));
    writeNodes(map, pathIn(partial, MapFile::Nodes));
    // Replace the old map only now that the new one is whole.
    const std::string old = dir + ".old";
    fs::remove_all(old, ec);
    if (fs::exists(dir)) fs::rename(dir, old, ec);
    if (ec) throw MapError(dir + ": cannot be replaced (" + ec.message() + ")");
    fs::rename(partial, dir, ec);
    if (ec) throw MapError(dir + ": cannot be written (" + ec.message() + ")");
    fs::remove_all(old, ec);
}

SavedMap readMap(const std::string& dir) {
    if (!fs::is_directory(dir)) throw MapError(dir + ": no such map folder");
    SavedMap map;
    const auto manifestPath = pathIn(dir, MapFile::Manifest);
    map.manifest = parseManifest(manifestPath);
    map.config = readText(pathIn(dir, MapFile::Config));
    const auto graphPath = pathIn(dir, MapFile::Graph);
    {
        mrpt::io::CFileInputStream stream;
        if (!stream.open(graphPath)) throw MapError(graphPath + ": cannot be read (missing?)");
        try {
            memguard::AllocationBudget budget(allocationLimit(stream.getTotalBytesCount()));
            auto archive = mrpt::serialization::archiveFrom(stream);
            static_cast<mrpt::serialization::CArchive&>(archive) >> map.graph;
        } catch (const std::exception& e) {
            throw MapError(graphPath + ": damaged (" + briefly(e) + ")");
        }
    }
    if (map.graph.nodes.size() != map.manifest.nodes || map.graph.edges.size() != map.manifest.edges) {
        throw MapError(graphPath + ": holds " + std::to_string(map.graph.nodes.size()) +
                       " nodes and " + std::to_string(map.graph.edges.size()) +
                       " edges, the manifest " + std::to_string(map.manifest.nodes) + " and " +
                       std::to_string(map.manifest.edges));
    }
    for (std::size_t id = 0; id < map.manifest.nodes; ++id) {
        if (!map.graph.nodes.count(static_cast<graphslam::TNodeID>(id)))
            throw MapError(graphPath + ": has no node " + std::to_string(id));
    }
    readNodes(pathIn(dir, MapFile::Nodes), map.manifest.nodes, map);
    const MapManifest counted = manifestOf(map);
    if (counted.keyframes != map.manifest.keyframes ||
        counted.magneticReadings != map.manifest.magneticReadings ||
        counted.segments != map.manifest.segments || counted.sessions != map.manifest.sessions) {
        throw MapError(pathIn(dir, MapFile::Nodes) +
                       ": its keyframes, readings, segments or sessions disagree with " +
                       manifestPath);
    }
    return map;
}

}  // namespace lodestone::maps
