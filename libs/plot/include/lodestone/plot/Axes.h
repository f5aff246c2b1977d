#pragma once

#include <opencv2/core.hpp>

#include <string>
#include <utility>
#include <vector>

namespace lodestone::plot {

/** Data limits of a plot, grown by the points it is shown. */
struct Bounds {
    double x0{1e300}, x1{-1e300}, y0{1e300}, y1{-1e300};
    void add(double x, double y);
    void add(const Bounds& other);
    bool empty() const { return x0 > x1 || y0 > y1; }
    /** Grown by `fraction` of its size on every side (at least `minimum` across). */
    Bounds padded(double fraction, double minimum = 1e-6) const;
};

/** One chart panel drawn into a region of a canvas: a frame with nice ticks and labels,
 * a title, and data drawn in data coordinates (clipped to the plot area).
 *
 * Usage: Axes a(canvas, rect); a.setLimits(bounds); a.drawFrame("title", "t [s]", "uT");
 * a.line(points, colour); a.legend({...}); */
class Axes {
  public:
    /** `leftMargin`: room for the y tick labels (wider for named rows) [px]. */
    Axes(cv::Mat3b& canvas, const cv::Rect& panel, int leftMargin = 62);

    void setLimits(const Bounds& limits);
    /** As setLimits, then widens one axis so a metre is as long in x as in y (maps). */
    void setLimitsEqualAspect(const Bounds& limits);
    const Bounds& limits() const { return limits_; }
    const cv::Rect& plotArea() const { return area_; }

    /** Frame, ticks, tick labels, axis labels and the title; grid lines across the plot area
     * unless `grid` is false (a map drawn before would be painted over). */
    void drawFrame(const std::string& title, const std::string& xLabel, const std::string& yLabel,
                   bool grid = true);

    /** Rows with names instead of a numeric y axis: row i spans y in [i, i+1], named at its
     * middle (a timeline of sensors). Call before drawFrame; set y limits to [0, rows]. */
    void setYCategories(std::vector<std::string> names) { categories_ = std::move(names); }

    cv::Point toPixel(double x, double y) const;
    cv::Point2d toPixelExact(double x, double y) const;  ///< unrounded, unclamped
    cv::Point2d toData(const cv::Point& pixel) const;

    void line(const std::vector<cv::Point2d>& points, const cv::Scalar& colour, int thickness = 1);
    void segment(const cv::Point2d& a, const cv::Point2d& b, const cv::Scalar& colour,
                 int thickness = 1);
    void dots(const std::vector<cv::Point2d>& points, const cv::Scalar& colour, int radius = 2);
    /** A marker that stays visible at any zoom: circle, cross or triangle. */
    enum class Marker { Circle, Cross, Triangle };
    void marker(const cv::Point2d& at, Marker shape, const cv::Scalar& colour, int size = 5);
    /** A shaded vertical band from x0 to x1 across the plot (gaps on a time axis). */
    void verticalSpan(double x0, double x1, const cv::Scalar& colour, double opacity = 0.35);
    /** The area between lo(x) and hi(x) (a min/max envelope). */
    void band(const std::vector<double>& x, const std::vector<double>& lo,
              const std::vector<double>& hi, const cv::Scalar& colour, double opacity = 0.3);
    /** Filled rectangle in data coordinates (a map cell). */
    void cell(double x0, double y0, double x1, double y1, const cv::Vec3b& colour);
    void text(const cv::Point2d& at, const std::string& s, const cv::Scalar& colour,
              double scale = 0.4);
    /** Entries in the upper left corner of the plot area. */
    void legend(const std::vector<std::pair<std::string, cv::Scalar>>& entries);

  private:
    cv::Mat3b& canvas_;
    cv::Rect panel_, area_;
    Bounds limits_;
    std::vector<std::string> categories_;
};

/** Text as every plot writes it (Hershey simplex, anti-aliased). */
void putLabel(cv::Mat3b& canvas, const std::string& s, const cv::Point& at, double scale = 0.42,
              const cv::Scalar& colour = cv::Scalar(0, 0, 0));

}  // namespace lodestone::plot
