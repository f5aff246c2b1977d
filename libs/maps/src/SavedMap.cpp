// A map folder: manifest.ini, config.ini, graph.bin (the graph, MRPT's serialization: exact),
// graph.graph (the same graph as MRPT's text format, for its tools) and nodes.bin (a header, then
// one CMapNode per node through MRPT's versioned serialization).
#include "MapFiles.h"

#include <lodestone/maps/MapNode.h>
#include <lodestone/maps/SavedMap.h>
#include <lodestone/memguard/AllocationBudget.h>
#include <mrpt/io/CFileInputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt/serialization/CArchive.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace lodestone::maps {

namespace fs = std::filesystem;
using detail::briefly;
using detail::manifestOf;
using detail::manifestText;
using detail::parseManifest;
using detail::readText;

namespace detail {

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw MapError(path + ": cannot be read (missing?)");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace detail

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

void writeText(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    if (!out.flush()) throw MapError(path + ": cannot be written");
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
