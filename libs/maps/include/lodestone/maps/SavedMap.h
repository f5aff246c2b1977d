#pragma once

#include <lodestone/graphslam/NodeStore.h>
#include <lodestone/graphslam/PoseGraph.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace lodestone::maps {

/** The map format this build writes, and the newest it reads. */
constexpr int kMapFormatVersion = 1;

/** Every file of a map folder: its name, what it holds. The one place the names live. */
enum class MapFile { Manifest, Config, Graph, GraphText, Nodes };
const char* fileName(MapFile file);
std::string pathIn(const std::string& dir, MapFile file);

/** What a map's manifest says of it (manifest.ini, [map]): the format, what made it, and
 * counts a reader checks the other files against. */
struct MapManifest {
    int formatVersion{kMapFormatVersion};
    std::string createdBy;     ///< e.g. "lodestone-slam 0.1.0"
    std::uint32_t sessions{1};
    std::size_t nodes{0}, edges{0}, keyframes{0}, magneticReadings{0};
    int segments{0};
    std::vector<std::string> magnetometers;  ///< the readings' sensor labels, sorted
    std::string nodeDecider, edgeDecider, optimizer;  ///< [graphslam] of the INI that made it
};

/** A map as saved: the graph (poses and every edge, MRPT's network of poses), each node's
 * record and session, the INI that shaped it (verbatim) and its manifest. */
struct SavedMap {
    MapManifest manifest;
    graphslam::Graph graph;
    std::vector<graphslam::NodeRecord> nodes;  ///< by node ID
    std::vector<std::uint32_t> sessions;       ///< by node ID
    std::string config;                        ///< the INI's text
};

/** A map folder that cannot be read: the message names the file and what is wrong. */
class MapError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/** Writes `map` as the folder `dir`: first into `dir.partial`, which then replaces `dir`
 * (a folder there before is removed only once the new one is whole), so a crash leaves the
 * last whole map. The manifest's counts are taken from the map. Throws MapError naming the
 * file on an I/O failure. */
void writeMap(const SavedMap& map, const std::string& dir);

/** Reads the folder `dir`. Throws MapError naming the file on a missing or damaged file, a
 * format version newer than kMapFormatVersion, or counts that disagree with the manifest. */
SavedMap readMap(const std::string& dir);

}  // namespace lodestone::maps
