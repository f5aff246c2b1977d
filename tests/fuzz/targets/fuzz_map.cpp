// A saved map folder (lodestone-slam --map-out; lodestone-inspect map): the input split at
// "%%" lines into manifest.ini, config.ini, graph.bin and nodes.bin. A map that reads must
// summarize, write and read back to the same counts (a round trip that changes it: abort).
#include <lodestone/maps/MapSummary.h>
#include <lodestone/maps/SavedMap.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "../FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace lodestone;
    const auto parts = fuzz::splitParts(data, size, 4);
    const std::string dir = fuzz::scratchDir() + "/map";
    std::filesystem::create_directories(dir);
    const maps::MapFile files[] = {maps::MapFile::Manifest, maps::MapFile::Config,
                                   maps::MapFile::Graph, maps::MapFile::Nodes};
    for (int k = 0; k < 4; ++k) fuzz::writeScratch(std::string("map/") + maps::fileName(files[k]), parts[k]);
    maps::SavedMap map;
    try {
        map = maps::readMap(dir);
    } catch (const maps::MapError&) {
        return 0;  // a clean refusal
    }
    std::ostringstream text;
    maps::printMapSummary(maps::summarizeMap(map, dir), text);
    const std::string again = fuzz::scratchDir() + "/map_again";
    maps::writeMap(map, again);
    const auto reread = maps::readMap(again);
    if (reread.nodes.size() != map.nodes.size() || reread.graph.edges.size() != map.graph.edges.size())
        std::abort();
    return 0;
}
