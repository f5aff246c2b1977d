#pragma once

#include <lodestone/inspect/RawlogSummary.h>
#include <lodestone/inspect/report/SensorTimeline.h>
#include <lodestone/inspect/report/Thumbnails.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace lodestone::inspect::report {

/** A picture on the page: file relative to the report folder, and what it shows. */
struct Figure {
    std::string file;
    std::string caption;
};

/** A section the caller adds to the page (e.g. a saved map, from the app that can read one):
 * its title, preformatted text, and pictures already written into the report folder. */
struct ExtraSection {
    std::string title;
    std::string text;
    std::vector<Figure> figures;
};

/** Everything index.html shows, gathered by the report's pass (RawlogReport). */
struct ReportPage {
    RawlogSummary summary;
    double gapFactor{5};
    std::vector<SensorTimeline> timelines;
    std::vector<Figure> rawlogFigures;  ///< timeline, magnetometers, odometry
    std::vector<Thumbnail> thumbnails;
    double thumbnailEvery{10};
    double depthMax{6};  ///< [m] top of the thumbnails' depth colour scale
    std::size_t unreadableFrames{0};
    /** The SLAM section, when --slam was given. */
    bool hasSlam{false};
    std::string slamDir;
    std::vector<std::pair<std::string, std::string>> slamFacts;
    std::vector<Figure> slamFigures;
    std::vector<std::string> slamNotes;  ///< files missing, readings not placed, ...
    std::vector<std::vector<std::string>> relocations;  ///< rows of the relocation table
    std::vector<ExtraSection> extraSections;            ///< after the SLAM section
};

/** Writes the page: self-contained HTML (inline style, no script, no address outside the
 * folder), to `path`.partial then renamed. Throws std::runtime_error naming the file. */
void writeReportHtml(const std::string& path, const ReportPage& page);

/** `v` with `decimals` decimals; "-" when not finite (a table cell with nothing to say). */
std::string fixedText(double v, int decimals);

/** `s` with &, <, >, " escaped. */
std::string htmlEscape(const std::string& s);

}  // namespace lodestone::inspect::report
