#pragma once

#include <lodestone/inspect/report/ReportHtml.h>

#include <optional>
#include <ostream>
#include <string>

namespace lodestone::inspect::report {

struct ReportOptions {
    std::string rawlog;
    std::string outDir;
    std::string slamDir;      ///< a lodestone-slam --out folder; empty: no SLAM section
    std::string groundTruth;  ///< TUM file; empty: SLAM_DIR/ground_truth.tum if there
    double thumbnailEvery{10.0};  ///< [s]
    double gapFactor{5.0};        ///< a gap: a step longer than this x the median step
    double fieldCell{0.1};        ///< [m] the field map's cells
    double depthMax{6.0};         ///< [m] top of the depth colour scale
    bool quiet{false}, terminal{false};  ///< progress bar
    /** Sections the caller adds after the SLAM section (their pictures already in outDir). */
    std::vector<ExtraSection> extraSections;
};

struct ReportResult {
    std::string index;                   ///< path of index.html
    std::optional<std::string> readError;  ///< the rawlog stopped early (the page says so)
    std::size_t entries{0}, thumbnails{0}, figures{0};
};

/** Reads the rawlog once (flat memory: one entry and the previous camera frame at a time) and
 * writes OUT_DIR/index.html with its PNGs and thumbnails beside it. A rawlog that stops early
 * still gets its page, of what was read, with the error on it. Throws std::runtime_error
 * naming the file when the rawlog cannot be opened, OUT_DIR cannot be written or the SLAM
 * folder has no trajectory.tum. */
ReportResult writeRawlogReport(const ReportOptions& options, std::ostream& progress);

}  // namespace lodestone::inspect::report
