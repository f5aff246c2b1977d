#pragma once
// The parts of a map folder's reading and writing that SavedMap.cpp and MapManifest.cpp share.
// Private to lodestone::maps.

#include <lodestone/maps/SavedMap.h>

#include <exception>
#include <string>

namespace lodestone::maps::detail {

/** An exception's message in one line: MRPT's "Message:" line where it has one. */
std::string briefly(const std::exception& e);

/** `map`'s manifest with its counts and labels taken from the map itself (MapError on a label
 * a manifest cannot hold). */
MapManifest manifestOf(const SavedMap& map);
/** manifest.ini's text. */
std::string manifestText(const MapManifest& m);
/** manifest.ini read strictly: MapError naming the file and key. */
MapManifest parseManifest(const std::string& path);
/** The file's bytes (MapError naming it when it cannot be read). */
std::string readText(const std::string& path);

}  // namespace lodestone::maps::detail
