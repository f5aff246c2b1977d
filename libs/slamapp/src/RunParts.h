#pragma once
// The three parts of a lodestone-slam run (runSlam): its sources opened and checked before any
// work (RunSources.cpp), the loop over their observations (RunLoop.cpp), and the outputs
// (RunOutputs.cpp, RunReport.cpp). Private to slamapp.

#include <lodestone/dense/Mesh.h>
#include <lodestone/graphslam/ReportJson.h>
#include <lodestone/graphslam/SlamEngine.h>
#include <lodestone/io/DataSource.h>
#include <lodestone/io/PrefetchingSource.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/sim/SimulatorSource.h>
#include <lodestone/slamapp/SlamRun.h>

#include <mrpt/math/TPoint3D.h>

#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace lodestone::slamapp::detail {

/** Input problems found before any work: the message is the whole story. */
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/** The sections a SLAM INI may hold: the engine's own and every registered class's. */
std::set<std::string> allowedSections();

/** What a run reads and drives, opened and checked before any work. */
struct RunInputs {
    std::unique_ptr<graphslam::SlamEngine> engine;
    std::unique_ptr<io::DataSource> source;  ///< (after the engine: its workers may call into it)
    sim::SimulatorSource* simulator{nullptr};  ///< `source`, when it is the simulator
    std::function<double()> fractionRead;      ///< of the rawlog, for the progress bar
    const io::PrefetchingSource* prefetcher{nullptr};  ///< its workers' time, for report.json
    std::size_t decodeThreads{0};
    std::unique_ptr<io::TumTrajectoryWriter> simTruth;  ///< --sim: the truth, as it is run
    std::vector<std::uint32_t> mapSessions;  ///< --map-in: the loaded map's sessions, by node
    /** The magnetometers a rawlog's first observations come from (none known: live, --sim). */
    std::set<std::string> prescannedMagnetometers;
};

/** The engine from the INI, the source (rawlog, simulator or live), the ground truth read, the
 * output folder made and emptied of a previous run's files. Throws InputError or
 * config::ConfigError naming the file, section or key. */
RunInputs openInputs(const SlamRunOptions& options);

/** A magnetometer reading kept for field_map.png, drawn once the trajectory is optimized. */
struct KeptReading {
    double time;
    mrpt::math::TPoint3D sensorOffset;
    double magnitude;
    std::size_t label;  ///< index into the labels
};

/** What the loop measured and kept. */
struct LoopOutcome {
    double wallSeconds{0};    ///< the loop and the engine's finish
    double dataSeconds{0};    ///< of data, from its first observation
    double sourceSeconds{0};  ///< waiting for the next observation
    std::vector<KeptReading> magnetic;  // 48 bytes a reading: 35 MB for an hour of two at 100 Hz
    std::vector<std::string> magneticLabels;
    std::size_t mapsSaved{0};  ///< while the run went on (--map-every)
    /** --mesh fused while the run went (RunningMesh): the mesh and what was fused. */
    std::optional<graphslam::JsonObject> runningMesh;
    dense::Mesh mesh;
    std::string runningMeshWhy;  ///< why `mesh` is empty
};

/** Feeds every observation to the engine until the source ends, --max-seconds or a fault in
 * the data (recorded in `result`, the run then finishes with what was processed), then
 * finishes the engine. */
LoopOutcome runLoop(RunInputs& in, const SlamRunOptions& options, std::ostream& err,
                    SlamRunResult& result);

/** Every output file, report.json last, and the summary lines on `out` (a warning on `err`).
 * Throws when a file cannot be written. */
void writeOutputs(const RunInputs& in, const LoopOutcome& loop, const SlamRunOptions& options,
                  std::ostream& out, std::ostream& err, SlamRunResult& result);

/** The saved map of `options.mapIn` loaded into `engine` (before any data; localize: the map
 * held fixed); its nodes' sessions. Throws InputError naming the file when it cannot be read,
 * was made by other deciders than the INI names, or holds magnetometer readings and none from
 * one of `runMagnetometers` (the labels the run's data was seen to carry; empty: not known). */
std::vector<std::uint32_t> loadMap(const SlamRunOptions& options, const std::string& configText,
                                   graphslam::SlamEngine& engine,
                                   const std::set<std::string>& runMagnetometers = {});

/** The run's map saved in options.mapOut (after every other output: a map that cannot be
 * written costs none of them; the error is reported, exit 1); what was saved, for report.json.
 * Extending a loaded map: the map's nodes and the run's that joined it, the run a new session. */
graphslam::JsonObject saveMap(const RunInputs& in, const SlamRunOptions& options,
                              std::ostream& err, SlamRunResult& result);

/** --mesh into mesh.ply (RunMesh.cpp): the mesh fused while the run went, or every keyframe's
 * frame read again from the source and fused at its node's optimized pose; what was fused, for
 * report.json. No mesh (no keyframe, no usable depth) is said on `err` and in the object, not
 * an error. */
graphslam::JsonObject writeMesh(const RunInputs& in, const LoopOutcome& loop, const SlamRunOptions& options,
                                std::ostream& err);

/** The text of the SLAM INI (what a saved map keeps). */
std::string configText(const SlamRunOptions& options);

/** report.json's "timing" object. */
graphslam::JsonObject timingJson(const graphslam::SlamEngine::Stats& stats, const LoopOutcome& loop,
                                 const io::PrefetchingSource* prefetcher);

}  // namespace lodestone::slamapp::detail
