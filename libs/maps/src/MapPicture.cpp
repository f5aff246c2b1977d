#include <lodestone/maps/MapPicture.h>
#include <lodestone/plot/Colormap.h>
#include <lodestone/plot/PlaneMap.h>

#include <algorithm>
#include <map>
#include <string>

namespace lodestone::maps {

cv::Mat3b drawMap(const SavedMap& map, double cell) {
    plot::ScalarGrid field(cell);
    plot::Bounds bounds;
    for (std::size_t id = 0; id < map.nodes.size(); ++id) {
        const auto& pose = map.graph.nodes.at(id);
        bounds.add(pose.x(), pose.y());
        for (const auto& r : map.nodes[id].magnetic) {
            // (the reading's own time is within the node's interval: the node's pose is close)
            const auto at = pose + r.sensorPose;
            field.add(at.x(), at.y(), r.field.norm());
        }
    }
    if (field.cells() > 0) bounds.add(field.bounds());
    cv::Mat3b canvas(720, 980, cv::Vec3b(255, 255, 255));
    plot::Axes axes(canvas, cv::Rect(0, 0, 880, 720));
    axes.setLimitsEqualAspect(bounds.empty() ? plot::Bounds{0, 1, 0, 1} : bounds.padded(0.05, 1.0));
    if (field.cells() > 0) {
        const plot::Colormap colours(field.quantile(0.02), field.quantile(0.98));
        field.forEach([&](double x0, double y0, double x1, double y1, double mean, std::size_t) {
            axes.cell(x0, y0, x1, y1, colours(mean));
        });
        colours.drawBar(canvas, cv::Rect(895, 60, 18, 600), "|B| [uT]");
    }
    axes.drawFrame("saved map: " + std::to_string(map.nodes.size()) + " nodes, " +
                       std::to_string(map.manifest.sessions) + " session(s)",
                   "x [m]", "y [m]", field.cells() == 0);
    // Each session's path, broken where a segment ends (a kidnap: not a path).
    std::map<std::uint32_t, std::vector<std::vector<cv::Point2d>>> paths;
    for (std::size_t id = 0; id < map.nodes.size(); ++id) {
        const auto& pose = map.graph.nodes.at(id);
        const std::uint32_t session = id < map.sessions.size() ? map.sessions[id] : 0;
        auto& pieces = paths[session];
        const bool continues = id > 0 && map.nodes[id - 1].segment == map.nodes[id].segment &&
                               !pieces.empty();
        if (!continues) pieces.emplace_back();
        pieces.back().emplace_back(pose.x(), pose.y());
    }
    // Keyframes under the paths; the first session widest, so that later ones over the same
    // ground leave it showing.
    const cv::Scalar grey(150, 150, 150);
    for (std::size_t id = 0; id < map.nodes.size(); ++id) {
        if (!map.nodes[id].keyframe || !map.nodes[id].features) continue;
        const auto& pose = map.graph.nodes.at(id);
        axes.marker({pose.x(), pose.y()}, plot::Axes::Marker::Circle, grey, 2);
    }
    // (a white edge first, so a path reads over the field's colours)
    const auto width = [](std::uint32_t session) { return session == 0 ? 5 : 2; };
    for (const auto& [session, pieces] : paths)
        for (const auto& piece : pieces) axes.line(piece, cv::Scalar(255, 255, 255), width(session) + 2);
    std::vector<std::pair<std::string, cv::Scalar>> legend;
    for (const auto& [session, pieces] : paths) {
        // (the first session black: the series' blue is lost on the field's)
        const cv::Scalar colour = session == 0 ? cv::Scalar(20, 20, 20) : plot::seriesColour(session);
        for (const auto& piece : pieces) axes.line(piece, colour, width(session));
        legend.emplace_back("session " + std::to_string(session), colour);
    }
    legend.emplace_back("keyframes (with features)", grey);
    axes.legend(legend);
    return canvas;
}

}  // namespace lodestone::maps
