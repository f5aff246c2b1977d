#pragma once

#include <lodestone/maps/SavedMap.h>

#include <ostream>
#include <string>

namespace lodestone::maps {

/** A saved map described (lodestone-inspect map DIR): its manifest, where its nodes lie, what
 * its nodes hold and what it costs on disk. */
struct MapSummary {
    MapManifest manifest;
    double minX{0}, minY{0}, maxX{0}, maxY{0};  ///< the nodes' extent [m]
    double pathLength{0};                        ///< summed over node steps within a segment [m]
    std::size_t features{0};                     ///< keyframe ORB features
    std::size_t bytesOnDisk{0};                  ///< every file of the folder
    std::vector<std::string> configSections;     ///< of config.ini, in file order
};

/** `map` described; `dir` is its folder (for the size on disk; empty: not counted). */
MapSummary summarizeMap(const SavedMap& map, const std::string& dir);
void printMapSummary(const MapSummary& summary, std::ostream& out);

}  // namespace lodestone::maps
