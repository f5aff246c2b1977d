#include <lodestone/slamapp/GraphPlot.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <limits>

namespace lodestone::slamapp {

cv::Mat3b plotGraph(const graphslam::Graph& graph,
                    const std::vector<graphslam::LoopClosure>& closures, int size) {
    cv::Mat3b img(size, size, cv::Vec3b(255, 255, 255));
    if (graph.nodes.empty()) return img;
    double x0 = std::numeric_limits<double>::max(), y0 = x0, x1 = -x0, y1 = -x0;
    for (const auto& [id, p] : graph.nodes) {
        x0 = std::min(x0, p.x());
        x1 = std::max(x1, p.x());
        y0 = std::min(y0, p.y());
        y1 = std::max(y1, p.y());
    }
    const double margin = 30, span = std::max({x1 - x0, y1 - y0, 1e-3});
    const double scale = (size - 2 * margin) / span;
    const auto px = [&](graphslam::TNodeID id) {
        const auto& p = graph.nodes.at(id);
        return cv::Point(static_cast<int>(margin + (p.x() - x0) * scale),
                         static_cast<int>(size - margin - (p.y() - y0) * scale));
    };
    for (const auto& [ends, c] : graph.edges) {
        if (ends.second == ends.first + 1 && graph.nodes.count(ends.first) &&
            graph.nodes.count(ends.second)) {
            cv::line(img, px(ends.first), px(ends.second), cv::Scalar(200, 80, 0), 1, cv::LINE_AA);
        }
    }
    for (const auto& lc : closures) {
        if (!graph.nodes.count(lc.from) || !graph.nodes.count(lc.to)) continue;
        const cv::Scalar colour = lc.rejected ? cv::Scalar(0, 0, 230) : cv::Scalar(0, 170, 0);
        cv::line(img, px(lc.from), px(lc.to), colour, 1, cv::LINE_AA);
    }
    cv::circle(img, px(graph.nodes.begin()->first), 5, cv::Scalar(0, 0, 0), 2);
    cv::putText(img, "nodes (blue), loop closures accepted (green) / rejected (red)",
                cv::Point(10, 20), cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 1,
                cv::LINE_AA);
    return img;
}

}  // namespace lodestone::slamapp
