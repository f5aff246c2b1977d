#include <lodestone/sim/ScenarioPlot.h>

#include <cstdio>
#include <opencv2/imgproc.hpp>

namespace lodestone::sim {

cv::Mat3b plotScenario(const SimulatorSource& source, double ppm) {
    const World& world = source.world();
    const FloorPlan& plan = world.floorPlan();
    const Eigen::Vector2d lo = plan.minCorner() - Eigen::Vector2d(0.5, 0.5);
    const Eigen::Vector2d hi = plan.maxCorner() + Eigen::Vector2d(0.5, 0.5);
    const int W = static_cast<int>((hi.x() - lo.x()) * ppm),
              H = static_cast<int>((hi.y() - lo.y()) * ppm);
    const int legend = 70;
    const auto px = [&](double x, double y) {
        return cv::Point(static_cast<int>((x - lo.x()) * ppm),
                         static_cast<int>((hi.y() - y) * ppm));
    };
    const auto& mags = source.scenario().magnetometers;
    const double z = mags.empty() ? 0.3 : mags.front().pose.z;

    // |B| on a grid at the sensor height.
    cv::Mat1f magnitude(H, W);
    for (int r = 0; r < H; ++r) {
        for (int c = 0; c < W; ++c) {
            const double x = lo.x() + (c + 0.5) / ppm, y = hi.y() - (r + 0.5) / ppm;
            magnitude(r, c) = static_cast<float>(world.field().at({x, y, z}).norm());
        }
    }
    // Colour scale from robust bounds, so one hot spot does not wash the map out.
    std::vector<float> sorted(magnitude.begin(), magnitude.end());
    std::sort(sorted.begin(), sorted.end());
    const float vmin = sorted[sorted.size() / 50], vmax = sorted[sorted.size() * 49 / 50];
    cv::Mat1b scaled;
    magnitude.convertTo(scaled, CV_8U, 255.0 / std::max(1e-3f, vmax - vmin),
                        -vmin * 255.0 / std::max(1e-3f, vmax - vmin));
    cv::Mat3b map;
    cv::applyColorMap(scaled, map, cv::COLORMAP_VIRIDIS);

    cv::Mat3b canvas(H + legend, std::max(W, 360), cv::Vec3b(255, 255, 255));
    map.copyTo(canvas(cv::Rect(0, 0, W, H)));

    // Walls: textured thick black, plain thin grey.
    for (const auto& w : plan.walls()) {
        const bool plain = world.wallStyle(w.surface) == SurfaceStyle::Plain;
        cv::line(canvas, px(w.a.x(), w.a.y()), px(w.b.x(), w.b.y()),
                 plain ? cv::Scalar(160, 160, 160) : cv::Scalar(0, 0, 0), plain ? 2 : 4);
    }
    // Path, sampled from the motion plan; carries dashed red.
    const MotionPlan& motion = source.plan();
    for (const auto& s : motion.segments()) {
        const auto a = poseOnSegment(s, s.t0), b = poseOnSegment(s, s.t1);
        if (s.kind == MotionSegment::Kind::Carry) {
            cv::line(canvas, px(a.x, a.y), px(b.x, b.y), cv::Scalar(40, 40, 230), 2, cv::LINE_AA);
            cv::circle(canvas, px(b.x, b.y), 7, cv::Scalar(40, 40, 230), 2, cv::LINE_AA);
            cv::line(canvas, px(b.x, b.y),
                     px(b.x + 0.5 * std::cos(b.yaw), b.y + 0.5 * std::sin(b.yaw)),
                     cv::Scalar(40, 40, 230), 2, cv::LINE_AA);
        } else if (s.kind == MotionSegment::Kind::Drive) {
            cv::line(canvas, px(a.x, a.y), px(b.x, b.y), cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
        }
    }
    const RobotPose start = motion.poseAt(0);
    cv::circle(canvas, px(start.x, start.y), 6, cv::Scalar(255, 255, 255), cv::FILLED, cv::LINE_AA);

    // Legend: the colour bar and its range.
    for (int c = 0; c < 256; ++c) {
        cv::Mat1b v(1, 1, static_cast<uchar>(c));
        cv::Mat3b col;
        cv::applyColorMap(v, col, cv::COLORMAP_VIRIDIS);
        cv::line(canvas, cv::Point(10 + c, H + 12), cv::Point(10 + c, H + 30),
                 cv::Scalar(col(0, 0)), 1);
    }
    char text[160];
    std::snprintf(text, sizeof(text), "|B| %.0f .. %.0f uT at z = %.2f m", vmin, vmax, z);
    cv::putText(canvas, text, cv::Point(10, H + 50), cv::FONT_HERSHEY_SIMPLEX, 0.45,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    std::snprintf(text, sizeof(text),
                  "%s: path white; walls textured black, plain grey; kidnaps red",
                  source.scenario().name.c_str());
    cv::putText(canvas, text, cv::Point(10, H + 66), cv::FONT_HERSHEY_SIMPLEX, 0.45,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    return canvas;
}

}  // namespace lodestone::sim
