#include <lodestone/inspect/TimeText.h>
#include <lodestone/inspect/report/ReportHtml.h>
#include <lodestone/io/RawlogPaths.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace lodestone::inspect::report {

namespace {
constexpr std::size_t kMaxEventRows = 200;  // gaps and backwards timestamps listed

const char* kStyle = R"(
body { font-family: "DejaVu Sans", sans-serif; margin: 24px; color: #222; max-width: 1200px; }
h1 { font-size: 22px; } h2 { font-size: 18px; margin-top: 32px; border-bottom: 1px solid #ccc; }
table { border-collapse: collapse; margin: 8px 0; font-size: 13px; }
th, td { border: 1px solid #ccc; padding: 3px 8px; text-align: right; }
th { background: #f0f0f0; } td.l, th.l { text-align: left; }
td.bad { background: #fde2e2; font-weight: bold; }
.error { background: #fde2e2; border: 1px solid #d33; padding: 8px; }
figure { margin: 12px 0; } figcaption { font-size: 13px; color: #555; }
img.chart { max-width: 100%; border: 1px solid #eee; }
.thumbs { display: flex; flex-wrap: wrap; gap: 8px; }
.thumbs figure { margin: 0; width: 250px; } .thumbs img { width: 240px; display: block; }
.note { font-size: 13px; color: #555; }
)";

class Page {
  public:
    std::ostringstream html;
    void row(const std::vector<std::string>& cells, bool header = false,
             const std::vector<bool>& bad = {}) {
        html << "<tr>";
        for (std::size_t i = 0; i < cells.size(); ++i) {
            const char* tag = header ? "th" : "td";
            html << "<" << tag;
            std::string cls = i == 0 ? "l" : "";
            if (i < bad.size() && bad[i]) cls += cls.empty() ? "bad" : " bad";
            if (!cls.empty()) html << " class=\"" << cls << "\"";
            html << ">" << htmlEscape(cells[i]) << "</" << tag << ">";
        }
        html << "</tr>\n";
    }
    void figure(const Figure& f) {
        html << "<figure><img class=\"chart\" src=\"" << htmlEscape(f.file) << "\" alt=\""
             << htmlEscape(f.caption) << "\"><figcaption>" << htmlEscape(f.caption)
             << "</figcaption></figure>\n";
    }
};

void summarySection(Page& p, const ReportPage& r) {
    const auto& s = r.summary;
    p.html << "<h2>Summary</h2>\n<table>\n";
    p.row({"file", s.path});
    p.row({"size on disk", std::to_string(s.fileBytes) + " bytes" +
                               (s.compressed ? " (gzip, " + std::to_string(s.uncompressedBytes) +
                                                   " uncompressed)"
                                             : " (plain)")});
    p.row({"format", io::toString(s.format)});
    p.row({"entries", std::to_string(s.entries)});
    if (s.first && s.last) {
        p.row({"first timestamp", timeText(*s.first)});
        p.row({"last timestamp", timeText(*s.last)});
        p.row({"time span", fixedText(mrpt::Clock::toDouble(*s.last) - mrpt::Clock::toDouble(*s.first), 3) + " s"});
    }
    for (const auto& [cls, n] : s.observationClasses) p.row({"observations: " + cls, std::to_string(n)});
    for (const auto& [cls, n] : s.entryClasses) p.row({"entries: " + cls, std::to_string(n)});
    p.html << "</table>\n";
}

void sensorSection(Page& p, const ReportPage& r) {
    p.html << "<h2>Sensors</h2>\n<p class=\"note\">A gap is a step longer than "
           << fixedText(r.gapFactor, 1)
           << " times the sensor's median step; backwards: a timestamp older than the newest "
              "before it (the size is how much older). Event sensors (wheel drops) have no "
              "gaps.</p>\n<table>\n";
    p.row({"label", "class", "count", "rate [Hz]", "span [s]", "median step [s]", "gaps",
           "largest gap [s]", "backwards", "largest backwards [s]", "wheel drops"},
          true);
    for (const auto& tl : r.timelines) {
        const auto st = r.summary.sensors.find(tl.label);
        const double rate = st == r.summary.sensors.end() ? NAN : st->second.meanRate();
        const double span = st == r.summary.sensors.end() ? NAN : st->second.span();
        std::size_t lifts = 0;
        for (const auto& d : tl.wheelDrops) lifts += d.second;
        p.row({tl.label.empty() ? "(no label)" : tl.label, tl.className, std::to_string(tl.count),
               fixedText(rate, 3), fixedText(span, 3), tl.eventDriven ? "-" : fixedText(tl.medianStep, 4),
               tl.eventDriven ? "-" : std::to_string(tl.gapCount),
               tl.gapCount ? fixedText(tl.largestGap, 3) : "-", std::to_string(tl.backwardCount),
               tl.backwardCount ? fixedText(tl.largestBackwards, 3) : "-",
               tl.wheelDrops.empty() ? "-" : std::to_string(lifts) + " lifted / " +
                                                 std::to_string(tl.wheelDrops.size() - lifts) + " down"},
              false,
              {false, false, false, false, false, false, tl.gapCount > 0, tl.gapCount > 0,
               tl.backwardCount > 0, tl.backwardCount > 0, false});
    }
    p.html << "</table>\n";
    // Every gap and backwards step, in time order per sensor (the first 200).
    std::size_t listed = 0, all = 0;
    Page events;
    for (const auto& tl : r.timelines) {
        all += tl.gapCount + tl.backwardCount;
        for (const auto& g : tl.gaps) {
            if (listed++ < kMaxEventRows) {
                events.row({tl.label, "gap", fixedText(g.time, 3), fixedText(g.size, 3)});
            }
        }
        for (const auto& b : tl.backwards) {
            if (listed++ < kMaxEventRows) {
                events.row({tl.label, "backwards", fixedText(b.time, 3), fixedText(b.size, 3)});
            }
        }
    }
    if (all) {
        p.html << "<h3>Gaps and backwards timestamps</h3>\n<table>\n";
        p.row({"sensor", "kind", "at [s since start]", "size [s]"}, true);
        p.html << events.html.str() << "</table>\n";
        if (all > kMaxEventRows) {
            p.html << "<p class=\"note\">" << kMaxEventRows << " of " << all << " listed.</p>\n";
        }
    }
}

void thumbnailSection(Page& p, const ReportPage& r) {
    if (r.thumbnails.empty() && r.unreadableFrames == 0) return;
    p.html << "<h2>Camera frames</h2>\n<p class=\"note\">Every " << fixedText(r.thumbnailEvery, 0)
           << " s and on both sides of each gap. Depth: viridis from 0 m (dark blue) to "
           << fixedText(r.depthMax, 1) << " m and beyond (yellow), black where the sensor gave no depth.";
    if (r.unreadableFrames) {
        p.html << " " << r.unreadableFrames << " picked frame(s) could not be loaded (missing external image files).";
    }
    p.html << "</p>\n<div class=\"thumbs\">\n";
    for (const auto& t : r.thumbnails) {
        p.html << "<figure>";
        if (!t.rgb.empty()) p.html << "<img src=\"" << htmlEscape(t.rgb) << "\" alt=\"colour\">";
        if (!t.depth.empty()) p.html << "<img src=\"" << htmlEscape(t.depth) << "\" alt=\"depth\">";
        p.html << "<figcaption>" << htmlEscape(t.label) << " at " << fixedText(t.time, 2) << " s ("
               << htmlEscape(t.why) << ")</figcaption></figure>\n";
    }
    p.html << "</div>\n";
}

void slamSection(Page& p, const ReportPage& r) {
    if (!r.hasSlam) return;
    p.html << "<h2>SLAM run</h2>\n<p class=\"note\">" << htmlEscape(r.slamDir) << "</p>\n<table>\n";
    for (const auto& [k, v] : r.slamFacts) p.row({k, v});
    p.html << "</table>\n";
    for (const auto& n : r.slamNotes) p.html << "<p class=\"note\">" << htmlEscape(n) << "</p>\n";
    for (const auto& f : r.slamFigures) p.figure(f);
    if (!r.relocations.empty()) {
        p.html << "<h3>Kidnaps and relocations</h3>\n<table>\n";
        p.row({"segment", "lifted [s since start]", "put down [s]", "relocated",
               "after put-down [s]", "travel [m]",
               "pose x, y [m], yaw [deg]"},
              true);
        for (const auto& row : r.relocations) p.row(row);
        p.html << "</table>\n";
    }
}
void extraSections(Page& p, const ReportPage& r) {
    for (const auto& x : r.extraSections) {
        p.html << "<h2>" << htmlEscape(x.title) << "</h2>\n";
        if (!x.text.empty()) p.html << "<pre>" << htmlEscape(x.text) << "</pre>\n";
        for (const auto& f : x.figures) p.figure(f);
    }
}
}  // namespace

std::string fixedText(double v, int decimals) {
    if (!std::isfinite(v)) return "-";
    char s[64];
    std::snprintf(s, sizeof s, "%.*f", decimals, v);
    return s;
}

std::string htmlEscape(const std::string& s) {
    std::string out;
    out.reserve(s.size());
    for (const char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

void writeReportHtml(const std::string& path, const ReportPage& r) {
    Page p;
    p.html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
           << "<title>Lodestone report: " << htmlEscape(r.summary.path) << "</title>\n"
           << "<style>" << kStyle << "</style>\n</head>\n<body>\n"
           << "<h1>Lodestone rawlog report</h1>\n<p class=\"note\">" << htmlEscape(r.summary.path)
           << " - written by lodestone-inspect report</p>\n";
    if (r.summary.error) {
        p.html << "<p class=\"error\">The rawlog could not be read to its end; everything below "
                  "is what was read before the fault: "
               << htmlEscape(*r.summary.error) << "</p>\n";
    }
    summarySection(p, r);
    sensorSection(p, r);
    for (const auto& f : r.rawlogFigures) p.figure(f);
    thumbnailSection(p, r);
    slamSection(p, r);
    extraSections(p, r);
    p.html << "</body>\n</html>\n";
    const std::string partial = io::partialPath(path);
    {
        std::ofstream out(partial);
        out << p.html.str();
        if (!out) throw std::runtime_error(partial + ": write failed");
    }
    io::commitPartial(path);
}

}  // namespace lodestone::inspect::report
