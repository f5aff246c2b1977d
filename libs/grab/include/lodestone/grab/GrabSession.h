#pragma once

#include <atomic>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

namespace lodestone::grab {

struct GrabOptions {
    std::string config;  ///< the grab INI
    std::string out;     ///< output prefix (PREFIX.rawlog.gz, PREFIX_Images/); empty: [global] rawlog_prefix
    double duration{std::numeric_limits<double>::infinity()};  ///< [s] of wall time
    std::string slamConfig;  ///< a lodestone-slam INI: run SLAM live on the stream
    std::string slamOut;     ///< its outputs (default PREFIX_slam)
    std::string slamMapIn;   ///< live SLAM starts in this saved map (localize; slamapp::SlamRunOptions::mapIn)
    double maxLag{0.3};      ///< [s] behind the newest observation, SLAM skips RGB-D frames
    bool slamView{false};    ///< live SLAM in MRPT's 3D window (slamapp::SlamRunOptions::view)
    bool slamMesh{false};    ///< live SLAM fuses a dense model as it goes (slamapp::SlamRunOptions::mesh)
    bool quiet{false}, terminal{false};
};

struct SensorSummary {
    std::string section, driver, state, error;
    std::size_t produced{0};
};

struct GrabResult {
    int exitCode{0};  ///< 0 ok; 1 a sensor failed to start, or died while grabbing
    std::string rawlog;
    std::vector<SensorSummary> sensors;
    std::size_t written{0}, late{0};
    double seconds{0};
    std::string stoppedBy;  ///< "signal", "duration", "sensors finished"
    // Live SLAM (with slamConfig)
    bool slam{false};
    int slamExitCode{0};
    std::size_t slamNodes{0}, slamClosures{0}, skippedFrames{0}, frames{0};
    double lagP50{0}, lagP99{0}, lagMax{0};
};

/** Runs a grab: every sensor section's driver on its own thread, observations written in time
 * order (ReorderingWriter) to PREFIX.rawlog.gz as they arrive, until `stop` is set (SIGINT /
 * SIGTERM in lodestone-grab), the duration is over or every sensor has finished. Then every
 * queued observation is written and the file closed. A sensor that fails to start: an error
 * naming its section before anything is written (exitCode 1); one that dies while grabbing is
 * logged with its section, the others go on, the summary says so (exitCode 1). Throws
 * config::ConfigError for a bad INI.
 *
 * With `slamConfig`, lodestone-slam's engine runs on the stream on a thread of its own, fed
 * what is written (LiveSlamFeed: RGB-D frames skipped while it lags more than `maxLag`), and
 * writes lodestone-slam's outputs in `slamOut` when the grab ends. */
GrabResult runGrab(const GrabOptions& options, const std::atomic<bool>& stop, std::ostream& out,
                   std::ostream& err);

}  // namespace lodestone::grab
