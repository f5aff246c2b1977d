#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace lodestone::inspect::report {

/** A time series summarized in a fixed number of bins, for a rawlog of unknown length read
 * once: bins start `initialWidth` seconds wide; a time beyond the last bin doubles the width,
 * merging neighbours, until it fits. Memory is `capacity` bins whatever the length; a plot of
 * `capacity` pixels or fewer loses nothing. `Bin` has `merge(const Bin&)`. */
template <class Bin>
class TimeBins {
  public:
    explicit TimeBins(std::size_t capacity = 2048, double initialWidth = 0.01)
        : bins_(std::max<std::size_t>(capacity, 2)), width_(initialWidth) {}

    /** The bin holding time `t` [s since the origin]; earlier than the origin: the first bin. */
    Bin& at(double t) {
        if (!std::isfinite(t) || t < 0) t = 0;
        while (t / width_ >= static_cast<double>(bins_.size())) halve();
        const auto i = static_cast<std::size_t>(t / width_);
        used_ = std::max(used_, i + 1);
        return bins_[i];
    }

    double width() const { return width_; }
    std::size_t used() const { return used_; }  ///< bins up to the last one touched
    const Bin& operator[](std::size_t i) const { return bins_[i]; }
    double start(std::size_t i) const { return static_cast<double>(i) * width_; }

  private:
    void halve() {
        const std::size_t n = bins_.size();
        for (std::size_t i = 0; i < n / 2; ++i) {
            Bin merged = bins_[2 * i];
            merged.merge(bins_[2 * i + 1]);
            bins_[i] = merged;
        }
        for (std::size_t i = n / 2; i < n; ++i) bins_[i] = Bin{};
        used_ = (used_ + 1) / 2;
        width_ *= 2;
    }

    std::vector<Bin> bins_;
    double width_;
    std::size_t used_{0};
};

/** How many samples fell in a bin. */
struct CountBin {
    std::size_t count{0};
    void merge(const CountBin& o) { count += o.count; }
};

/** Minimum, maximum and mean of the values in a bin. */
struct EnvelopeBin {
    double min{std::numeric_limits<double>::infinity()};
    double max{-std::numeric_limits<double>::infinity()};
    double sum{0};
    std::size_t count{0};
    void add(double v) {
        if (!std::isfinite(v)) return;
        min = std::min(min, v);
        max = std::max(max, v);
        sum += v;
        ++count;
    }
    void merge(const EnvelopeBin& o) {
        min = std::min(min, o.min);
        max = std::max(max, o.max);
        sum += o.sum;
        count += o.count;
    }
    double mean() const { return count ? sum / static_cast<double>(count) : std::nan(""); }
};

}  // namespace lodestone::inspect::report
