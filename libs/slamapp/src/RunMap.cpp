// A run and saved maps: one loaded before any data (--map-in), the run's own written after
// every other output (--map-out).
#include "RunParts.h"

#include <lodestone/maps/MapSnapshot.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace lodestone::slamapp::detail {

namespace {

/** What a map's INI and the run's must agree on: the deciders and the loop closers they host. */
std::string shapeOf(const std::string& iniText) {
    const mrpt::config::CConfigFileMemory ini(iniText);
    const auto word = [&](const char* section, const char* key, const char* fallback) {
        return ini.read_string_first_word(section, key, fallback);
    };
    std::string children = ini.read_string("CompositeERD", "children", "");
    children = children.substr(0, children.find_first_of(";#"));
    std::istringstream names(children);
    std::string list;
    for (std::string n; names >> n;) list += (list.empty() ? "" : " ") + n;
    return "node_decider " + word("graphslam", "node_decider", "FusedOdometryNRD") +
           ", edge_decider " + word("graphslam", "edge_decider", "CompositeERD") + " (" + list +
           "), optimizer " + word("graphslam", "optimizer", "CeresGSO");
}

}  // namespace

std::string configText(const SlamRunOptions& options) {
    std::ifstream in(options.config, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::vector<std::uint32_t> loadMap(const SlamRunOptions& options, const std::string& runConfig,
                                   graphslam::SlamEngine& engine,
                                   const std::set<std::string>& runMagnetometers) {
    maps::SavedMap map;
    try {
        map = maps::readMap(options.mapIn);
    } catch (const maps::MapError& e) {
        throw InputError(e.what());
    }
    std::string mapShape;
    try {
        mapShape = shapeOf(map.config);
    } catch (const std::exception& e) {
        throw InputError(maps::pathIn(options.mapIn, maps::MapFile::Config) + ": " + e.what());
    }
    const std::string runShape = shapeOf(runConfig);
    if (mapShape != runShape) {
        throw InputError(options.mapIn + ": made with " + mapShape + "; " + options.config +
                         " has " + runShape + " (a map is used with the deciders that made it)");
    }
    // The magnetic closers match a reading with the same magnetometer's: a run whose
    // magnetometers the map never heard would never relocate in it.
    const auto& heard = map.manifest.magnetometers;
    for (const auto& label : runMagnetometers) {
        if (heard.empty() || std::find(heard.begin(), heard.end(), label) != heard.end()) continue;
        std::string list;
        for (const auto& h : heard) list += (list.empty() ? "" : ", ") + h;
        throw InputError(options.mapIn + ": made with magnetometers " + list + "; " +
                         options.rawlog + " has readings from " + label +
                         " (a map is used with the sensors that made it)");
    }
    try {
        engine.startInMap(map.graph, std::move(map.nodes), !options.extendMap);
    } catch (const std::logic_error& e) {
        throw InputError(options.config + ": " + e.what());
    }
    return map.sessions;
}

graphslam::JsonObject saveMap(const RunInputs& in, const SlamRunOptions& options,
                              std::ostream& err, SlamRunResult& result) {
    const auto& engine = *in.engine;
    graphslam::JsonObject saved;
    saved.set("dir", options.mapOut);
    try {
        const std::string createdBy = std::string("lodestone-slam ") + LODESTONE_VERSION;
        maps::SavedMap map;
        // The odometry edges as the solves used them: a map reloaded and solved again (extend)
        // keeps its shape without this run's estimates.
        graphslam::Graph graph = engine.graph();
        engine.optimizer().calibrateEdges(graph);
        if (engine.mapNodes() == 0) {
            map = maps::mapOf(graph, engine.nodes(), configText(options), createdBy);
        } else {
            // The map, and the run's nodes that joined it (a segment that never found itself
            // on the map adds nothing), the run as a session of its own.
            std::vector<std::uint32_t> sessions = in.mapSessions;
            const std::uint32_t run =
                sessions.empty() ? 1 : *std::max_element(sessions.begin(), sessions.end()) + 1;
            sessions.resize(engine.nodes().size(), run);
            const auto mapNodes = engine.mapNodes();
            map = maps::mapOf(graph, engine.nodes(), sessions,
                              [&](graphslam::TNodeID id) {
                                  return id < mapNodes || engine.relocalizer().groupOf(id) == 0;
                              },
                              configText(options), createdBy);
            saved.set("session", static_cast<std::size_t>(run))
                .set("run_nodes_kept", map.nodes.size() - mapNodes);
        }
        maps::writeMap(map, options.mapOut);
        saved.set("nodes", map.nodes.size()).set("edges", map.graph.edges.size());
    } catch (const std::exception& e) {
        err << "lodestone-slam: " << e.what() << "\n";
        saved.set("error", e.what());
        result.exitCode = 1;
        if (result.error.empty()) result.error = e.what();
    }
    return saved;
}

}  // namespace lodestone::slamapp::detail
