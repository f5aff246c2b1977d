#pragma once

#include <lodestone/plot/Axes.h>

#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

namespace lodestone::plot {

/** Values placed on the plane (x, y [m]) and averaged per square cell - |B| over the floor.
 * Memory grows with the area covered, not with the number of values. */
class ScalarGrid {
  public:
    explicit ScalarGrid(double cellSize);
    void add(double x, double y, double value);  ///< non-finite input is ignored

    double cellSize() const { return cell_; }
    std::size_t cells() const { return cells_.size(); }
    std::size_t values() const { return values_; }
    Bounds bounds() const;  ///< of the occupied cells' corners
    /** The `q`-quantile (0..1) of the cell means: a colour scale robust to a few outliers. */
    double quantile(double q) const;
    /** Calls `f(x0, y0, x1, y1, mean, count)` for every occupied cell. */
    void forEach(const std::function<void(double, double, double, double, double, std::size_t)>& f) const;

  private:
    struct Cell {
        double sum{0};
        std::size_t count{0};
    };
    static std::int64_t key(std::int32_t i, std::int32_t j);
    double cell_;
    std::size_t values_{0};
    std::unordered_map<std::int64_t, Cell> cells_;
};

/** What a plane map is called and how its values read. */
struct PlaneMapStyle {
    std::string title;
    std::string unit;  ///< colour bar label, e.g. "|B| [uT]"
    int width{900}, height{700};
};

/** The grid's cell means colour-mapped (viridis, 2 %-98 % of the cells), the path's pieces
 * drawn over it (thin grey), a colour bar, metres on both axes, equal aspect. */
cv::Mat3b renderPlaneMap(const ScalarGrid& grid,
                         const std::vector<std::vector<cv::Point2d>>& pathPieces,
                         const PlaneMapStyle& style);

}  // namespace lodestone::plot
