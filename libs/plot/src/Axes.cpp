#include <lodestone/plot/Axes.h>
#include <lodestone/plot/Ticks.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace lodestone::plot {

namespace {
// Room around the plot area for tick labels, axis labels and the title [px].
constexpr int kRight = 14, kTop = 26, kBottom = 40;
const cv::Scalar kInk(40, 40, 40), kGrid(228, 228, 228);
// Liang-Barsky: the part of segment ab inside the box, in place; false when none is.
bool clipToBox(cv::Point2d& a, cv::Point2d& b, double x0, double y0, double x1, double y1) {
    if (!std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(b.x) || !std::isfinite(b.y)) {
        return false;
    }
    const double dx = b.x - a.x, dy = b.y - a.y;
    double t0 = 0, t1 = 1;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {a.x - x0, x1 - a.x, a.y - y0, y1 - a.y};
    for (int k = 0; k < 4; ++k) {
        if (p[k] == 0) {
            if (q[k] < 0) return false;
            continue;
        }
        const double r = q[k] / p[k];
        if (p[k] < 0) {
            t0 = std::max(t0, r);
        } else {
            t1 = std::min(t1, r);
        }
        if (t0 > t1) return false;
    }
    b = a + cv::Point2d(dx, dy) * t1;
    a = a + cv::Point2d(dx, dy) * t0;
    return true;
}
}  // namespace

void Bounds::add(double x, double y) {
    if (!std::isfinite(x) || !std::isfinite(y)) return;
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
}

void Bounds::add(const Bounds& o) {
    if (o.empty()) return;
    add(o.x0, o.y0);
    add(o.x1, o.y1);
}

Bounds Bounds::padded(double fraction, double minimum) const {
    if (empty()) return Bounds{0, 1, 0, 1};
    Bounds b = *this;
    const auto grow = [&](double& lo, double& hi) {
        const double span = std::max(hi - lo, minimum);
        const double mid = 0.5 * (lo + hi);
        lo = mid - span * (0.5 + fraction);
        hi = mid + span * (0.5 + fraction);
    };
    grow(b.x0, b.x1);
    grow(b.y0, b.y1);
    return b;
}

void putLabel(cv::Mat3b& canvas, const std::string& s, const cv::Point& at, double scale,
              const cv::Scalar& colour) {
    cv::putText(canvas, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
}

Axes::Axes(cv::Mat3b& canvas, const cv::Rect& panel, int leftMargin)
    : canvas_(canvas),
      panel_(panel),
      area_(panel.x + leftMargin, panel.y + kTop, std::max(panel.width - leftMargin - kRight, 10),
            std::max(panel.height - kTop - kBottom, 10)),
      limits_{0, 1, 0, 1} {}

void Axes::setLimits(const Bounds& limits) {
    limits_ = limits.empty() ? Bounds{0, 1, 0, 1} : limits;
    if (limits_.x1 - limits_.x0 <= 0) limits_ = limits_.padded(0, 1e-6);
    if (limits_.y1 - limits_.y0 <= 0) limits_ = limits_.padded(0, 1e-6);
}

void Axes::setLimitsEqualAspect(const Bounds& limits) {
    setLimits(limits);
    const double mx = (limits_.x1 - limits_.x0) / area_.width;
    const double my = (limits_.y1 - limits_.y0) / area_.height;
    const double m = std::max(mx, my);  // metres per pixel on both axes
    const double cx = 0.5 * (limits_.x0 + limits_.x1), cy = 0.5 * (limits_.y0 + limits_.y1);
    limits_.x0 = cx - 0.5 * m * area_.width;
    limits_.x1 = cx + 0.5 * m * area_.width;
    limits_.y0 = cy - 0.5 * m * area_.height;
    limits_.y1 = cy + 0.5 * m * area_.height;
}

cv::Point2d Axes::toPixelExact(double x, double y) const {
    const double u = (x - limits_.x0) / (limits_.x1 - limits_.x0);
    const double v = (y - limits_.y0) / (limits_.y1 - limits_.y0);
    return {area_.x + u * (area_.width - 1), area_.y + (1 - v) * (area_.height - 1)};
}

cv::Point Axes::toPixel(double x, double y) const {
    const cv::Point2d p = toPixelExact(x, y);
    // Far-away points are clamped well outside the area (markers and cells are clipped by
    // OpenCV; lines are clipped exactly in line()).
    const auto px = [](double q) {
        return static_cast<int>(std::lround(std::isfinite(q) ? std::clamp(q, -2e4, 2e4) : -2e4));
    };
    return {px(p.x), px(p.y)};
}

cv::Point2d Axes::toData(const cv::Point& p) const {
    const double u = static_cast<double>(p.x - area_.x) / (area_.width - 1);
    const double v = 1 - static_cast<double>(p.y - area_.y) / (area_.height - 1);
    return {limits_.x0 + u * (limits_.x1 - limits_.x0), limits_.y0 + v * (limits_.y1 - limits_.y0)};
}

void Axes::drawFrame(const std::string& title, const std::string& xLabel,
                     const std::string& yLabel, bool grid) {
    const auto xt = niceTicks(limits_.x0, limits_.x1, std::max(2, area_.width / 80));
    const auto yt = niceTicks(limits_.y0, limits_.y1, std::max(2, area_.height / 45));
    const double xs = xt.size() > 1 ? xt[1] - xt[0] : 1, ys = yt.size() > 1 ? yt[1] - yt[0] : 1;
    for (const double t : xt) {
        const int x = toPixel(t, 0).x;
        if (grid) cv::line(canvas_, {x, area_.y}, {x, area_.y + area_.height - 1}, kGrid);
        cv::line(canvas_, {x, area_.y + area_.height}, {x, area_.y + area_.height + 4}, kInk);
        const std::string s = tickLabel(t, xs);
        putLabel(canvas_, s, {x - 4 * static_cast<int>(s.size()), area_.y + area_.height + 17}, 0.38);
    }
    if (categories_.empty()) {
        for (const double t : yt) {
            const int y = toPixel(0, t).y;
            if (grid) cv::line(canvas_, {area_.x, y}, {area_.x + area_.width - 1, y}, kGrid);
            cv::line(canvas_, {area_.x - 4, y}, {area_.x, y}, kInk);
            const std::string s = tickLabel(t, ys);
            putLabel(canvas_, s, {area_.x - 8 - 8 * static_cast<int>(s.size()), y + 4}, 0.38);
        }
    } else {
        for (std::size_t i = 0; i < categories_.size(); ++i) {
            const int y = toPixel(0, static_cast<double>(i)).y;
            if (grid) cv::line(canvas_, {area_.x, y}, {area_.x + area_.width - 1, y}, kGrid);
            putLabel(canvas_, categories_[i], {panel_.x + 4, toPixel(0, i + 0.5).y + 4}, 0.4);
        }
    }
    cv::rectangle(canvas_, area_, kInk);
    putLabel(canvas_, title, {area_.x, panel_.y + 17}, 0.48);
    putLabel(canvas_, xLabel, {area_.x + area_.width / 2 - 4 * static_cast<int>(xLabel.size()),
                               area_.y + area_.height + 34}, 0.4);
    putLabel(canvas_, yLabel, {panel_.x + 4, area_.y - 6}, 0.4);
}

void Axes::line(const std::vector<cv::Point2d>& points, const cv::Scalar& colour, int thickness) {
    cv::Mat3b roi = canvas_(area_);
    const cv::Point2d offset(area_.x, area_.y);
    for (std::size_t i = 1; i < points.size(); ++i) {
        cv::Point2d a = toPixelExact(points[i - 1].x, points[i - 1].y) - offset;
        cv::Point2d b = toPixelExact(points[i].x, points[i].y) - offset;
        // Clipped in floating point first: OpenCV's anti-aliased lines work in 16.16 fixed
        // point, so an endpoint far off the canvas would overflow rather than clip.
        if (!clipToBox(a, b, -8.0, -8.0, area_.width + 8.0, area_.height + 8.0)) continue;
        const cv::Point pa(static_cast<int>(std::lround(a.x)), static_cast<int>(std::lround(a.y)));
        const cv::Point pb(static_cast<int>(std::lround(b.x)), static_cast<int>(std::lround(b.y)));
        if (pa == pb && i + 1 < points.size()) continue;
        cv::line(roi, pa, pb, colour, thickness, cv::LINE_AA);
    }
}

void Axes::segment(const cv::Point2d& a, const cv::Point2d& b, const cv::Scalar& colour,
                   int thickness) {
    line({a, b}, colour, thickness);
}

void Axes::dots(const std::vector<cv::Point2d>& points, const cv::Scalar& colour, int radius) {
    cv::Mat3b roi = canvas_(area_);
    const cv::Point offset(area_.x, area_.y);
    for (const auto& p : points) {
        cv::circle(roi, toPixel(p.x, p.y) - offset, radius, colour, cv::FILLED, cv::LINE_AA);
    }
}

void Axes::marker(const cv::Point2d& at, Marker shape, const cv::Scalar& colour, int size) {
    cv::Mat3b roi = canvas_(area_);
    const cv::Point c = toPixel(at.x, at.y) - cv::Point(area_.x, area_.y);
    switch (shape) {
        case Marker::Circle: cv::circle(roi, c, size, colour, 2, cv::LINE_AA); break;
        case Marker::Cross:
            cv::line(roi, c + cv::Point(-size, -size), c + cv::Point(size, size), colour, 2, cv::LINE_AA);
            cv::line(roi, c + cv::Point(-size, size), c + cv::Point(size, -size), colour, 2, cv::LINE_AA);
            break;
        case Marker::Triangle: {
            const std::vector<cv::Point> t = {c + cv::Point(0, -size), c + cv::Point(size, size),
                                              c + cv::Point(-size, size)};
            cv::fillConvexPoly(roi, t, colour, cv::LINE_AA);
        } break;
    }
}

void Axes::verticalSpan(double x0, double x1, const cv::Scalar& colour, double opacity) {
    int a = toPixel(x0, 0).x, b = toPixel(x1, 0).x;
    if (b < a) std::swap(a, b);
    a = std::max(a, area_.x);
    b = std::min(std::max(b, a + 1), area_.x + area_.width - 1);  // at least a pixel wide
    if (b <= a) return;
    cv::Mat3b strip = canvas_(cv::Rect(a, area_.y, b - a + 1, area_.height));
    cv::Mat3b fill(strip.size(), cv::Vec3b(static_cast<unsigned char>(colour[0]),
                                           static_cast<unsigned char>(colour[1]),
                                           static_cast<unsigned char>(colour[2])));
    cv::addWeighted(fill, opacity, strip, 1 - opacity, 0, strip);
}

void Axes::band(const std::vector<double>& x, const std::vector<double>& lo,
                const std::vector<double>& hi, const cv::Scalar& colour, double opacity) {
    const std::size_t n = std::min({x.size(), lo.size(), hi.size()});
    if (n < 2) return;
    cv::Mat3b roi = canvas_(area_);
    cv::Mat3b layer = roi.clone();
    const cv::Point offset(area_.x, area_.y);
    for (std::size_t i = 1; i < n; ++i) {
        if (!std::isfinite(lo[i - 1]) || !std::isfinite(lo[i])) continue;
        const std::vector<cv::Point> quad = {
            toPixel(x[i - 1], lo[i - 1]) - offset, toPixel(x[i], lo[i]) - offset,
            toPixel(x[i], hi[i]) - offset, toPixel(x[i - 1], hi[i - 1]) - offset};
        cv::fillPoly(layer, std::vector<std::vector<cv::Point>>{quad}, colour);
    }
    cv::addWeighted(layer, opacity, roi, 1 - opacity, 0, roi);
}

void Axes::cell(double x0, double y0, double x1, double y1, const cv::Vec3b& colour) {
    cv::Mat3b roi = canvas_(area_);
    const cv::Point offset(area_.x, area_.y);
    cv::Point a = toPixel(x0, y1) - offset, b = toPixel(x1, y0) - offset;
    cv::rectangle(roi, a, b, cv::Scalar(colour), cv::FILLED);
}

void Axes::text(const cv::Point2d& at, const std::string& s, const cv::Scalar& colour,
                double scale) {
    putLabel(canvas_, s, toPixel(at.x, at.y) + cv::Point(4, -4), scale, colour);
}

void Axes::legend(const std::vector<std::pair<std::string, cv::Scalar>>& entries) {
    if (entries.empty()) return;
    std::size_t longest = 0;
    for (const auto& e : entries) longest = std::max(longest, e.first.size());
    const cv::Rect box(area_.x + 4, area_.y + 4, 40 + 7 * static_cast<int>(longest),
                       8 + 16 * static_cast<int>(entries.size()));
    cv::rectangle(canvas_, box & area_, cv::Scalar(255, 255, 255), cv::FILLED);
    cv::rectangle(canvas_, box & area_, cv::Scalar(200, 200, 200));
    int y = area_.y + 18;
    for (const auto& [name, colour] : entries) {
        cv::line(canvas_, {area_.x + 8, y - 4}, {area_.x + 26, y - 4}, colour, 3, cv::LINE_AA);
        putLabel(canvas_, name, {area_.x + 32, y}, 0.4);
        y += 16;
    }
}

}  // namespace lodestone::plot
