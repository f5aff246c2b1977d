#pragma once

#include <opencv2/core.hpp>

#include <string>

namespace lodestone::plot {

/** A perceptually uniform colour scale (OpenCV's viridis) over [lo, hi]: what depth images and
 * the field map are drawn with. Values outside clamp to the ends; NaN is grey. A range of one
 * value becomes [value - 0.5, value + 0.5]. */
class Colormap {
  public:
    Colormap(double lo, double hi);
    cv::Vec3b operator()(double value) const;
    double lo() const { return lo_; }
    double hi() const { return hi_; }

    /** Draws the scale as a vertical bar in `box` of `canvas`, ticks and `label` to its right. */
    void drawBar(cv::Mat3b& canvas, const cv::Rect& box, const std::string& label) const;

  private:
    double lo_, hi_;
    cv::Mat3b lut_;  // 256 x 1
};

/** One of ten distinguishable colours for series `index` (BGR; repeats after ten). */
cv::Scalar seriesColour(std::size_t index);

}  // namespace lodestone::plot
