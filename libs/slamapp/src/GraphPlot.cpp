#include <lodestone/plot/Axes.h>
#include <lodestone/slamapp/GraphPlot.h>

namespace lodestone::slamapp {

cv::Mat3b plotGraph(const graphslam::Graph& graph,
                    const std::vector<graphslam::LoopClosure>& closures, int size) {
    cv::Mat3b img(size, size, cv::Vec3b(255, 255, 255));
    plot::Bounds bounds;
    for (const auto& [id, p] : graph.nodes) bounds.add(p.x(), p.y());
    plot::Axes axes(img, cv::Rect(0, 0, size, size));
    axes.setLimitsEqualAspect(bounds.empty() ? plot::Bounds{0, 1, 0, 1} : bounds.padded(0.04, 1.0));
    axes.drawFrame("pose graph from above", "x [m]", "y [m]");
    const auto at = [&](graphslam::TNodeID id) {
        const auto& p = graph.nodes.at(id);
        return cv::Point2d(p.x(), p.y());
    };
    const cv::Scalar chain(200, 80, 0), accepted(0, 170, 0), rejected(0, 0, 230);
    for (const auto& [ends, c] : graph.edges) {
        if (ends.second == ends.first + 1 && graph.nodes.count(ends.first) &&
            graph.nodes.count(ends.second)) {
            axes.segment(at(ends.first), at(ends.second), chain);
        }
    }
    for (const auto& lc : closures) {
        if (!graph.nodes.count(lc.from) || !graph.nodes.count(lc.to)) continue;
        axes.segment(at(lc.from), at(lc.to), lc.rejected ? rejected : accepted);
    }
    if (!graph.nodes.empty()) {
        axes.marker(at(graph.nodes.begin()->first), plot::Axes::Marker::Circle, cv::Scalar(0, 0, 0), 6);
    }
    axes.legend({{"nodes in order", chain},
                 {"loop closures kept", accepted},
                 {"loop closures rejected", rejected},
                 {"first node", cv::Scalar(0, 0, 0)}});
    return img;
}

}  // namespace lodestone::slamapp
