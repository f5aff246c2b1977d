#include <lodestone/plot/Colormap.h>
#include <lodestone/plot/PlaneMap.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace lodestone::plot {

ScalarGrid::ScalarGrid(double cellSize) : cell_(cellSize > 0 ? cellSize : 0.1) {}

std::int64_t ScalarGrid::key(std::int32_t i, std::int32_t j) {
    // Through unsigned: shifting a negative value is undefined.
    const std::uint64_t k = (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) |
                            static_cast<std::uint32_t>(j);
    return static_cast<std::int64_t>(k);
}

void ScalarGrid::add(double x, double y, double value) {
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(value)) return;
    const double limit = std::numeric_limits<std::int32_t>::max() / 2.0;
    const double fi = std::floor(x / cell_), fj = std::floor(y / cell_);
    if (std::abs(fi) > limit || std::abs(fj) > limit) return;  // not a place on a floor
    auto& c = cells_[key(static_cast<std::int32_t>(fi), static_cast<std::int32_t>(fj))];
    c.sum += value;
    ++c.count;
    ++values_;
}

void ScalarGrid::forEach(
    const std::function<void(double, double, double, double, double, std::size_t)>& f) const {
    for (const auto& [k, c] : cells_) {
        const auto u = static_cast<std::uint64_t>(k);
        const auto i = static_cast<std::int32_t>(static_cast<std::uint32_t>(u >> 32));
        const auto j = static_cast<std::int32_t>(static_cast<std::uint32_t>(u & 0xffffffffu));
        f(i * cell_, j * cell_, (i + 1) * cell_, (j + 1) * cell_, c.sum / c.count, c.count);
    }
}

Bounds ScalarGrid::bounds() const {
    Bounds b;
    forEach([&](double x0, double y0, double x1, double y1, double, std::size_t) {
        b.add(x0, y0);
        b.add(x1, y1);
    });
    return b;
}

double ScalarGrid::quantile(double q) const {
    std::vector<double> means;
    means.reserve(cells_.size());
    for (const auto& [k, c] : cells_) means.push_back(c.sum / c.count);
    if (means.empty()) return std::nan("");
    const auto at = static_cast<std::size_t>(std::clamp(q, 0.0, 1.0) * (means.size() - 1));
    std::nth_element(means.begin(), means.begin() + static_cast<std::ptrdiff_t>(at), means.end());
    return means[at];
}

cv::Mat3b renderPlaneMap(const ScalarGrid& grid,
                         const std::vector<std::vector<cv::Point2d>>& pathPieces,
                         const PlaneMapStyle& style) {
    constexpr int kBarRoom = 110;  // colour bar and its tick labels on the right
    Bounds limits = grid.bounds();
    for (const auto& piece : pathPieces) {
        for (const auto& p : piece) limits.add(p.x, p.y);
    }
    limits = limits.padded(0.04, 1.0);
    // A map taller than wide gets a narrower picture rather than empty sides (equal aspect),
    // but not narrower than its title.
    constexpr int kMargins = 62 + 14, kTitleAndAxis = 26 + 40;
    const double aspect = (limits.x1 - limits.x0) / (limits.y1 - limits.y0);
    const int width = std::clamp(
        static_cast<int>(aspect * (style.height - kTitleAndAxis)) + kMargins + kBarRoom, 780,
        style.width);
    cv::Mat3b canvas(style.height, width, cv::Vec3b(255, 255, 255));
    Axes axes(canvas, cv::Rect(0, 0, width - kBarRoom, style.height));
    axes.setLimitsEqualAspect(limits);
    const double lo = grid.quantile(0.02), hi = grid.quantile(0.98);
    const Colormap colours(std::isfinite(lo) ? lo : 0.0, std::isfinite(hi) ? hi : 1.0);
    // The plot area in light grey: where no reading was placed.
    cv::rectangle(canvas, axes.plotArea(), cv::Scalar(238, 238, 238), cv::FILLED);
    grid.forEach([&](double x0, double y0, double x1, double y1, double mean, std::size_t) {
        axes.cell(x0, y0, x1, y1, colours(mean));
    });
    char info[160];
    std::snprintf(info, sizeof info, "%s (%zu values, %.2f m cells)", style.title.c_str(),
                  grid.values(), grid.cellSize());
    axes.drawFrame(info, "x [m]", "y [m]", /*grid=*/false);
    for (const auto& piece : pathPieces) axes.line(piece, cv::Scalar(90, 90, 90), 1);
    const cv::Rect area = axes.plotArea();
    colours.drawBar(canvas, cv::Rect(width - kBarRoom + 20, area.y + 20, 18, area.height - 40),
                    style.unit);
    return canvas;
}

}  // namespace lodestone::plot
