// A map's manifest (manifest.ini, [map]): what the other files hold, written from the map and
// read back strictly - the counts a reader checks the rest against, and the format version.
#include "MapFiles.h"

#include <lodestone/config/IniSection.h>
#include <lodestone/maps/MapNode.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace lodestone::maps::detail {

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


}  // namespace lodestone::maps::detail
