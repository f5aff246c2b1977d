#pragma once

#include <lodestone/io/DataSource.h>

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <ostream>
#include <string>

namespace lodestone::slamapp {

/** What one `lodestone-slam` run is asked to do. */
struct SlamRunOptions {
    std::string rawlog;       ///< input rawlog, or
    std::string scenario;     ///< a simulator scenario INI run directly, or
    /** observations as they come (lodestone-grab --slam): next() waits for them, nullptr ends
     * the run. No pre-scan of the input; the rest as for a rawlog. */
    std::shared_ptr<io::DataSource> live;
    /** Called after every observation with the graph's node and loop-closure counts (for a
     * caller's status line; on the run's thread). */
    std::function<void(std::size_t nodes, std::size_t loopClosures)> onProgress;
    std::string config;       ///< the SLAM INI ([graphslam] and the deciders' sections)
    std::string outDir;
    std::string groundTruth;  ///< TUM file for the ATE (with --sim: the simulator's own)
    /** Where the map is saved at the end (maps::writeMap: a folder, replaced whole); empty:
     * not saved. */
    std::string mapOut;
    /** With mapOut: also saved every this many seconds of data while the run goes on (each
     * time whole: a crash leaves the last one); 0: only at the end. */
    double mapEvery{0};
    /** A saved map to start in (maps::readMap), held fixed: the run relocalizes in it globally
     * (no start pose), then tracks with closures to its nodes; trajectory.tum holds the run's
     * nodes once they joined the map, in the map's frame. Empty: the run starts from nothing. */
    std::string mapIn;
    /** With mapIn: extend the map instead (not held fixed: closures may correct it; the run's
     * nodes that joined it are saved with it by mapOut, as a session of their own). */
    bool extendMap{false};
    double maxSeconds{std::numeric_limits<double>::infinity()};  ///< of data, from its start
    /** Frames read, decoded and prepared ahead on other threads (io::PrefetchingSource); 0:
     * all in the frame loop. Results are the same either way. (32, a second of a 30 Hz camera,
     * kept the readers busier through the loop's longer frames from the page cache - 2.22x real
     * time against 2.14x - but not measurably from a cold disk, for 50-80 MB more:
     * docs/results/throughput.md.) */
    std::size_t decodeAhead{8};
    /** Threads reading and decoding ahead (with decodeAhead > 0); 0: one per core the
     * process may run on (its affinity: `taskset -c 0` gives one). */
    std::size_t decodeThreads{0};
    bool quiet{false};
    bool terminal{false};  ///< draw the progress bar in place
    /** MRPT's 3D window with the run as it goes (view::LiveView); without a display the run
     * goes on without it, with a warning. */
    bool view{false};
    /** At the end, the window stays until it is closed (a user at a terminal). */
    bool viewKeepOpen{false};
    /** The dense model: after the last optimization every keyframe's frame is read again and
     * fused at its optimized pose into mesh.ply ([dense] keys of the INI). */
    bool mesh{false};
    /** The unit the rawlog's CObservationMagnetometer numbers are really in, when a tool wrote
     * them in another than the class's microtesla (lodestone-slam --magnetic-unit): every
     * reading is converted as it is read. Empty: microtesla. Either way, where the deciders take
     * magnetometers, a rawlog whose field is not Earth's in that unit is refused before any
     * work (obs::implausibleFieldMagnitude). */
    std::string magneticUnit;
};

/** The checks runSlam makes of a SLAM INI before any work (the file, its sections, every
 * decider's keys): throws naming the file, section and key. For callers that must refuse a
 * bad INI before doing anything else (lodestone-grab --slam). */
void checkSlamConfig(const std::string& configPath);
/** The same, and the saved map `mapIn` read and checked against it (as SlamRunOptions::mapIn
 * is before a run): throws naming the file. */
void checkSlamConfig(const std::string& configPath, const std::string& mapIn);

/** What came out, for callers and tests (report.json holds it all). */
struct SlamRunResult {
    int exitCode{0};                ///< 0 ok; 1 bad input or a fault in the data
    std::optional<double> ateRmse;  ///< [m] when ground truth was available
    std::size_t nodes{0}, loopClosures{0};
    std::string error;  ///< what stopped the run early, if anything
};

/** Runs the engine over the rawlog or the simulated scenario and writes, in `outDir`:
 * trajectory.tum (every node), graph.graph (MRPT text format), map.ply (keyframe clouds),
 * report.json (parameters, counts, timings, ATE), graph.png and, with ground truth,
 * trajectory.png (and ground_truth.tum for --sim). Configuration mistakes and a rawlog that
 * lacks the observations the deciders need stop before any work; a fault in the data stops the
 * run there, and everything processed until then is still optimized and written. Messages go to
 * `err`, the summary to `out`. */
SlamRunResult runSlam(const SlamRunOptions& options, std::ostream& out, std::ostream& err);

}  // namespace lodestone::slamapp
