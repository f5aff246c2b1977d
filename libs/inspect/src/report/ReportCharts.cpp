#include <lodestone/inspect/report/ReportCharts.h>
#include <lodestone/plot/Axes.h>
#include <lodestone/plot/Colormap.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

namespace lodestone::inspect::report {

using plot::Axes;
using plot::Bounds;

namespace {
const cv::Scalar kGapColour(60, 60, 230), kBackwardsColour(0, 140, 255), kLifted(40, 40, 220),
    kDown(60, 160, 60), kDensity(160, 110, 40);

// Envelope bins as plot series: bin centres, min, max, mean (empty bins skipped).
struct Series {
    std::vector<double> t, lo, hi;
    std::vector<cv::Point2d> mean;
};
Series seriesOf(const TimeBins<EnvelopeBin>& bins) {
    Series s;
    for (std::size_t i = 0; i < bins.used(); ++i) {
        const auto& b = bins[i];
        if (!b.count) continue;
        const double t = bins.start(i) + 0.5 * bins.width();
        s.t.push_back(t);
        s.lo.push_back(b.min);
        s.hi.push_back(b.max);
        s.mean.emplace_back(t, b.mean());
    }
    return s;
}
// The node at `time` (files print times to the microsecond, so matching allows that much).
std::optional<cv::Point2d> nodeAt(const std::map<double, cv::Point2d>& nodes, double time) {
    auto it = nodes.lower_bound(time - 2e-6);
    if (it == nodes.end() || it->first > time + 2e-6) return std::nullopt;
    return it->second;
}
}  // namespace

cv::Mat3b timelineChart(const std::vector<SensorTimeline>& sensors, double span) {
    const int rows = static_cast<int>(std::max<std::size_t>(sensors.size(), 1));
    cv::Mat3b canvas(80 + 36 * rows, 1100, cv::Vec3b(255, 255, 255));
    Axes axes(canvas, cv::Rect(0, 0, canvas.cols, canvas.rows), 160);
    axes.setLimits(Bounds{0, std::max(span, 1e-3), 0, static_cast<double>(rows)});
    std::vector<std::string> names;
    // Row 0 at the bottom: list the sensors top to bottom in label order.
    for (std::size_t i = 0; i < sensors.size(); ++i) {
        names.push_back(sensors[sensors.size() - 1 - i].label.empty() ? "(no label)"
                                                                       : sensors[sensors.size() - 1 - i].label);
    }
    axes.setYCategories(names);
    axes.drawFrame("samples over time: density (blue), gaps (red), backwards timestamps (orange)",
                   "time since the first timestamp [s]", "");
    for (std::size_t k = 0; k < sensors.size(); ++k) {
        const auto& s = sensors[k];
        const double row = static_cast<double>(sensors.size() - 1 - k);
        if (s.eventDriven) {  // its samples are the events: markers on a line, no density
            axes.segment({0, row + 0.5}, {std::max(span, 1e-3), row + 0.5}, cv::Scalar(200, 200, 200), 1);
        }
        // Display bins at least 3 px and 10 median steps wide, so a steady sensor draws a
        // flat bar; the bar's height is the bin's count against the median full bin.
        const double pxSeconds = std::max(span, 1e-3) / axes.plotArea().width;
        const std::size_t merge = static_cast<std::size_t>(std::max(
            1.0, std::ceil(std::max(3 * pxSeconds, 10 * s.medianStep) / s.density.width())));
        std::vector<std::pair<double, std::size_t>> bars;  // start, count
        for (std::size_t i = 0; !s.eventDriven && i < s.density.used(); i += merge) {
            std::size_t n = 0;
            for (std::size_t j = i; j < std::min(i + merge, s.density.used()); ++j) n += s.density[j].count;
            bars.emplace_back(s.density.start(i), n);
        }
        std::vector<std::size_t> full;
        for (const auto& b : bars) {
            if (b.second) full.push_back(b.second);
        }
        std::size_t typical = 1;
        if (!full.empty()) {
            std::nth_element(full.begin(), full.begin() + full.size() / 2, full.end());
            typical = std::max<std::size_t>(full[full.size() / 2], 1);
        }
        const double barWidth = merge * s.density.width();
        for (const auto& [x0, n] : bars) {
            if (!n) continue;
            // Within a quarter of the typical count is "steady" (bin phase alone moves a count
            // by one); below, the bar dips in proportion; well above, it stands taller.
            const double ratio = static_cast<double>(n) / static_cast<double>(typical);
            const double h = 0.6 * (ratio < 0.75 ? ratio : ratio > 1.5 ? 1.25 : 1.0);
            axes.cell(x0, row + 0.1, x0 + barWidth, row + 0.1 + std::max(h, 0.08),
                      cv::Vec3b(static_cast<unsigned char>(kDensity[0]),
                                static_cast<unsigned char>(kDensity[1]),
                                static_cast<unsigned char>(kDensity[2])));
        }
        for (const auto& g : s.gaps) {
            axes.cell(g.time, row + 0.02, g.time + g.size, row + 0.98, cv::Vec3b(170, 170, 255));
            axes.segment({g.time, row + 0.02}, {g.time, row + 0.98}, kGapColour, 1);
        }
        for (const auto& b : s.backwards) {
            axes.marker({b.time, row + 0.5}, Axes::Marker::Triangle, kBackwardsColour, 6);
        }
        for (const auto& [t, lifted] : s.wheelDrops) {
            axes.marker({t, row + 0.5}, lifted ? Axes::Marker::Cross : Axes::Marker::Circle,
                        lifted ? kLifted : kDown, 5);
        }
    }
    return canvas;
}

cv::Mat3b magnetometerChart(const MagnetometerSeries& m) {
    cv::Mat3b canvas(560, 1100, cv::Vec3b(255, 255, 255));
    const char* names[] = {"x", "y", "z"};
    {
        Axes axes(canvas, cv::Rect(0, 0, canvas.cols, 300));
        Bounds b;
        std::vector<Series> s;
        for (int c = 0; c < 3; ++c) {
            s.push_back(seriesOf(m.channels[c]));
            for (std::size_t i = 0; i < s[c].t.size(); ++i) {
                b.add(s[c].t[i], s[c].lo[i]);
                b.add(s[c].t[i], s[c].hi[i]);
            }
        }
        axes.setLimits(b.padded(0.02, 1.0));
        axes.drawFrame(m.label + ": field components in the sensor frame (band: min-max per bin)",
                       "", "[uT]");
        std::vector<std::pair<std::string, cv::Scalar>> legend;
        for (int c = 0; c < 3; ++c) {
            axes.band(s[c].t, s[c].lo, s[c].hi, plot::seriesColour(c), 0.25);
            axes.line(s[c].mean, plot::seriesColour(c), 1);
            legend.push_back({std::string("B") + names[c], plot::seriesColour(c)});
        }
        axes.legend(legend);
    }
    {
        Axes axes(canvas, cv::Rect(0, 300, canvas.cols, 260));
        const Series s = seriesOf(m.channels[3]);
        Bounds b;
        for (std::size_t i = 0; i < s.t.size(); ++i) {
            b.add(s.t[i], s.lo[i]);
            b.add(s.t[i], s.hi[i]);
        }
        axes.setLimits(b.padded(0.02, 1.0));
        axes.drawFrame(m.label + ": |B|", "time since the first timestamp [s]", "[uT]");
        axes.band(s.t, s.lo, s.hi, cv::Scalar(60, 60, 60), 0.2);
        axes.line(s.mean, cv::Scalar(30, 30, 30), 1);
    }
    return canvas;
}

cv::Mat3b odometryChart(const std::vector<OdometryPath>& paths) {
    cv::Mat3b canvas(640, 760, cv::Vec3b(255, 255, 255));
    Axes axes(canvas, cv::Rect(0, 0, canvas.cols, canvas.rows));
    Bounds b;
    for (const auto& p : paths) {
        for (const auto& q : p.points) b.add(q.x(), q.y());
    }
    axes.setLimitsEqualAspect(b.padded(0.05, 1.0));
    axes.drawFrame("odometry from above (each source's own frame; start o, end x)", "x [m]", "y [m]");
    std::vector<std::pair<std::string, cv::Scalar>> legend;
    for (std::size_t k = 0; k < paths.size(); ++k) {
        const auto& p = paths[k];
        std::vector<cv::Point2d> pts;
        for (const auto& q : p.points) pts.emplace_back(q.x(), q.y());
        const cv::Scalar c = plot::seriesColour(k);
        axes.line(pts, c, 2);
        if (!pts.empty()) {
            axes.marker(pts.front(), Axes::Marker::Circle, c, 6);
            axes.marker(pts.back(), Axes::Marker::Cross, c, 6);
        }
        char name[160];
        std::snprintf(name, sizeof name, "%s (%.1f m)", p.label.c_str(), p.length);
        legend.push_back({name, c});
    }
    axes.legend(legend);
    return canvas;
}

cv::Mat3b graphChart(const SlamOutputs& slam) {
    cv::Mat3b canvas(760, 900, cv::Vec3b(255, 255, 255));
    Axes axes(canvas, cv::Rect(0, 0, canvas.cols, canvas.rows));
    Bounds b;
    for (const auto& p : slam.trajectory) b.add(p.pose.x(), p.pose.y());
    axes.setLimitsEqualAspect(b.padded(0.05, 1.0));
    axes.drawFrame("pose graph: nodes by segment (grey shades), loop closures by decider", "x [m]",
                   "y [m]");
    // Node positions by time (closures.csv names nodes by ID and time; trajectory.tum has the
    // times), segments from nodes.csv when present.
    std::map<double, cv::Point2d> at;
    for (const auto& p : slam.trajectory) at[p.timestamp] = {p.pose.x(), p.pose.y()};
    std::map<double, int> segmentAt;
    for (const auto& n : slam.nodes) segmentAt[n.timestamp] = n.segment;
    std::vector<cv::Point2d> run;
    int segment = -1;
    const auto flush = [&] {
        const int shade = 150 - 50 * (segment % 3);
        axes.line(run, cv::Scalar(shade, shade, shade), 2);
        run.clear();
    };
    for (const auto& p : slam.trajectory) {
        const auto s = segmentAt.find(p.timestamp);
        const int seg = s == segmentAt.end() ? 0 : s->second;
        if (seg != segment && !run.empty()) flush();
        segment = seg;
        run.emplace_back(p.pose.x(), p.pose.y());
    }
    if (!run.empty()) flush();
    std::map<std::string, std::size_t> sources;
    std::map<std::string, std::pair<std::size_t, std::size_t>> counts;  // kept, not kept
    for (const auto& c : slam.closures) {
        const auto colourIndex = sources.emplace(c.source, sources.size()).first->second;
        const cv::Scalar colour = plot::seriesColour(colourIndex);
        const auto from = nodeAt(at, c.fromTime), to = nodeAt(at, c.toTime);
        auto& n = counts[c.source];
        (c.kept ? n.first : n.second)++;
        if (!from || !to) continue;
        if (c.kept) {
            axes.segment(*from, *to, colour, 2);
        } else {
            axes.segment(*from, *to, colour, 1);
            axes.marker((*from + *to) * 0.5, Axes::Marker::Cross, colour, 4);
        }
    }
    for (const auto& k : slam.kidnaps) {
        if (k.relocated) axes.marker({k.x, k.y}, Axes::Marker::Triangle, cv::Scalar(0, 0, 0), 7);
    }
    std::vector<std::pair<std::string, cv::Scalar>> legend;
    for (const auto& [name, index] : sources) {
        char line[160];
        std::snprintf(line, sizeof line, "%s: %zu kept, %zu not kept (x)", name.c_str(),
                      counts[name].first, counts[name].second);
        legend.push_back({line, plot::seriesColour(index)});
    }
    if (!slam.kidnaps.empty()) legend.push_back({"relocated after a kidnap (triangle)", cv::Scalar(0, 0, 0)});
    axes.legend(legend);
    return canvas;
}

cv::Mat3b nodeTimeChart(const std::vector<NodeRow>& nodes) {
    cv::Mat3b canvas(340, 1100, cv::Vec3b(255, 255, 255));
    Axes axes(canvas, cv::Rect(0, 0, canvas.cols, canvas.rows));
    Bounds b;
    const double t0 = nodes.empty() ? 0 : nodes.front().timestamp;
    std::vector<cv::Point2d> plain, keyframes;
    for (const auto& n : nodes) {
        if (!std::isfinite(n.engineMs)) continue;
        b.add(n.timestamp - t0, 0);
        b.add(n.timestamp - t0, n.engineMs);
        (n.keyframe ? keyframes : plain).emplace_back(n.timestamp - t0, n.engineMs);
    }
    axes.setLimits(b.padded(0.02, 1.0));
    axes.drawFrame("engine time per node (from the node before to this one's registration)",
                   "node time since the first node [s]", "[ms]");
    axes.dots(plain, plot::seriesColour(0), 2);
    axes.dots(keyframes, plot::seriesColour(1), 2);
    axes.legend({{"node", plot::seriesColour(0)}, {"keyframe", plot::seriesColour(1)}});
    return canvas;
}

}  // namespace lodestone::inspect::report
