#include <lodestone/plot/Colormap.h>
#include <lodestone/plot/Ticks.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace lodestone::plot {

Colormap::Colormap(double lo, double hi) : lo_(lo), hi_(hi) {
    // One value (a flat field): shown mid-scale on a scale one unit wide.
    if (!(hi_ - lo_ > 1e-9 * std::max({1.0, std::abs(lo_), std::abs(hi_)}))) {
        lo_ -= 0.5;
        hi_ = lo_ + 1.0;
    }
    cv::Mat1b ramp(256, 1);
    for (int i = 0; i < 256; ++i) ramp(i) = static_cast<unsigned char>(i);
    cv::applyColorMap(ramp, lut_, cv::COLORMAP_VIRIDIS);
}

cv::Vec3b Colormap::operator()(double value) const {
    if (!std::isfinite(value)) return {160, 160, 160};
    const double t = std::clamp((value - lo_) / (hi_ - lo_), 0.0, 1.0);
    return lut_(static_cast<int>(std::lround(t * 255)), 0);
}

void Colormap::drawBar(cv::Mat3b& canvas, const cv::Rect& box, const std::string& label) const {
    const cv::Rect inside = box & cv::Rect(0, 0, canvas.cols, canvas.rows);
    for (int y = inside.y; y < inside.y + inside.height; ++y) {
        const double t = 1.0 - static_cast<double>(y - box.y) / std::max(box.height - 1, 1);
        const cv::Vec3b c = (*this)(lo_ + t * (hi_ - lo_));
        cv::line(canvas, {inside.x, y}, {inside.x + inside.width - 1, y}, cv::Scalar(c), 1);
    }
    cv::rectangle(canvas, box, cv::Scalar(60, 60, 60), 1);
    const auto ticks = niceTicks(lo_, hi_, 5);
    const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0;
    for (const double t : ticks) {
        const int y = box.y + static_cast<int>(std::lround((hi_ - t) / (hi_ - lo_) * (box.height - 1)));
        cv::line(canvas, {box.x + box.width, y}, {box.x + box.width + 4, y}, cv::Scalar(60, 60, 60));
        cv::putText(canvas, tickLabel(t, step), {box.x + box.width + 7, y + 4},
                    cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    }
    cv::putText(canvas, label, {box.x - 4, box.y - 8}, cv::FONT_HERSHEY_SIMPLEX, 0.42,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
}

cv::Scalar seriesColour(std::size_t index) {
    // Tableau's ten, in BGR.
    static const cv::Scalar palette[] = {{180, 119, 31}, {14, 127, 255}, {44, 160, 44},
                                         {40, 39, 214},  {189, 103, 148}, {75, 86, 140},
                                         {194, 119, 227}, {127, 127, 127}, {34, 189, 188},
                                         {207, 190, 23}};
    return palette[index % 10];
}

}  // namespace lodestone::plot
