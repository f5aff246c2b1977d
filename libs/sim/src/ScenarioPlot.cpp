#include <lodestone/plot/Axes.h>
#include <lodestone/plot/Colormap.h>
#include <lodestone/sim/ScenarioPlot.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lodestone::sim {

namespace {
constexpr int kLeft = 62, kRight = 110, kTopBottom = 80;  // axes' labels and the colour bar
constexpr double kMinMapWidth = 640;  // [px]
}

cv::Mat3b plotScenario(const SimulatorSource& source, double pixelsPerMetre) {
    const World& world = source.world();
    const FloorPlan& plan = world.floorPlan();
    const Eigen::Vector2d lo = plan.minCorner() - Eigen::Vector2d(0.5, 0.5);
    const Eigen::Vector2d hi = plan.maxCorner() + Eigen::Vector2d(0.5, 0.5);
    // A small world drawn larger: the map at least kMinMapWidth pixels across.
    const double ppm = std::max(pixelsPerMetre, kMinMapWidth / (hi.x() - lo.x()));
    const int W = static_cast<int>((hi.x() - lo.x()) * ppm),
              H = static_cast<int>((hi.y() - lo.y()) * ppm);
    const auto& mags = source.scenario().magnetometers;
    const double z = mags.empty() ? 0.3 : mags.front().pose.z;

    // |B| on a grid at the sensor height, one cell a pixel at `ppm`.
    const double step = 1.0 / ppm;
    std::vector<float> magnitude(static_cast<std::size_t>(W) * H);
    for (int r = 0; r < H; ++r) {
        for (int c = 0; c < W; ++c) {
            const double x = lo.x() + (c + 0.5) * step, y = lo.y() + (r + 0.5) * step;
            magnitude[static_cast<std::size_t>(r) * W + c] =
                static_cast<float>(world.field().at({x, y, z}).norm());
        }
    }
    // Colour scale from robust bounds, so one hot spot does not wash the map out.
    std::vector<float> sorted = magnitude;
    std::sort(sorted.begin(), sorted.end());
    const double vmin = sorted[sorted.size() / 50], vmax = sorted[sorted.size() * 49 / 50];
    const plot::Colormap colours(vmin, vmax);

    cv::Mat3b canvas(H + kTopBottom, std::max(W + kLeft + kRight, 420), cv::Vec3b(255, 255, 255));
    plot::Axes axes(canvas, cv::Rect(0, 0, canvas.cols - kRight, canvas.rows));
    axes.setLimitsEqualAspect({lo.x(), hi.x(), lo.y(), hi.y()});
    for (int r = 0; r < H; ++r) {
        for (int c = 0; c < W; ++c) {
            const double x = lo.x() + c * step, y = lo.y() + r * step;
            axes.cell(x, y, x + step, y + step, colours(magnitude[static_cast<std::size_t>(r) * W + c]));
        }
    }
    axes.drawFrame(source.scenario().name + ": |B| at z = " + [&] {
        char s[32];
        std::snprintf(s, sizeof s, "%.2f m", z);
        return std::string(s);
    }(), "x [m]", "y [m]", /*grid=*/false);

    // Walls: textured thick black, plain thin grey.
    const cv::Scalar textured(0, 0, 0), plain(160, 160, 160), path(255, 255, 255),
        carried(40, 40, 230);
    for (const auto& w : plan.walls()) {
        const bool isPlain = world.wallStyle(w.surface) == SurfaceStyle::Plain;
        axes.segment({w.a.x(), w.a.y()}, {w.b.x(), w.b.y()}, isPlain ? plain : textured,
                     isPlain ? 2 : 4);
    }
    // The path, from the motion plan; a carry (kidnap) red, ending in the put-down's heading.
    const MotionPlan& motion = source.plan();
    for (const auto& s : motion.segments()) {
        const auto a = poseOnSegment(s, s.t0), b = poseOnSegment(s, s.t1);
        if (s.kind == MotionSegment::Kind::Carry) {
            axes.segment({a.x, a.y}, {b.x, b.y}, carried, 2);
            axes.marker({b.x, b.y}, plot::Axes::Marker::Circle, carried, 7);
            axes.segment({b.x, b.y}, {b.x + 0.5 * std::cos(b.yaw), b.y + 0.5 * std::sin(b.yaw)},
                         carried, 2);
        } else if (s.kind == MotionSegment::Kind::Drive) {
            axes.segment({a.x, a.y}, {b.x, b.y}, path, 1);
        }
    }
    const RobotPose start = motion.poseAt(0);
    axes.marker({start.x, start.y}, plot::Axes::Marker::Circle, path, 6);
    std::vector<std::pair<std::string, cv::Scalar>> legend = {
        {"path, start (white)", cv::Scalar(120, 120, 120)}, {"wall: textured", textured}};
    const auto& walls = plan.walls();
    if (std::any_of(walls.begin(), walls.end(), [&](const auto& w) {
            return world.wallStyle(w.surface) == SurfaceStyle::Plain;
        }))
        legend.push_back({"wall: plain", plain});
    if (!source.scenario().kidnaps.empty()) legend.push_back({"kidnap: carried, put down", carried});
    axes.legend(legend);
    const cv::Rect area = axes.plotArea();
    colours.drawBar(canvas, cv::Rect(area.x + area.width + 14, area.y, 16, area.height), "|B| [uT]");
    return canvas;
}

}  // namespace lodestone::sim
