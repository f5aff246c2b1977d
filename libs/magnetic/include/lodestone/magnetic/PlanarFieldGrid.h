#pragma once

#include <lodestone/magnetic/GaussianProcess1D.h>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace lodestone::magnetic {

struct PlanarFieldGridParams {
    double cell{0.05};  ///< [m] grid step (a sixth of a typical 0.3 m length scale)
    /** Cells within this many length scales of a reading hold the GP's prediction; beyond,
     * the map knows nothing (the prior), its covariance there below e^-4.5 of sigma_f^2. */
    double reachScales{3.0};
    std::size_t neighbours{16};        ///< readings each cell's local GP is conditioned on
    std::size_t maxCells{20'000'000};  ///< a map whose band needs more is refused
};

/** The field over the floor as a map a pose can be scored against anywhere, in any heading:
 * a Gaussian process (squared-exponential kernel, isotropic in the plane, the readings' mean as
 * its prior mean) of world-frame field vectors at planar positions, evaluated once per cell of
 * a grid on the band within `reachScales` length scales of a reading. Each cell conditions on
 * its `neighbours` nearest readings (a local GP: the kernel is negligible beyond them), so
 * building costs O(cells) and a lookup a hash probe. The variance is the latent one (the
 * channels share the kernel), the reading noise not included. */
class PlanarFieldGrid {
  public:
    using Params = PlanarFieldGridParams;
    /** `points` (n x 2) [m], `field` (n x 3) [uT] world frame. Throws std::invalid_argument
     * on an empty or mismatched set, a non-finite value, invalid hyperparameters or a band of
     * more than `maxCells`. */
    PlanarFieldGrid(const Eigen::MatrixX2d& points, const Eigen::MatrixX3d& field,
                    const GpHyperparameters& h, const Params& p = {});

    struct Prediction {
        Eigen::Vector3f mean;
        float variance{0};  ///< latent, per channel [uT^2]
        bool known{false};  ///< inside the band (else the prior)
    };
    Prediction at(double x, double y) const;
    /** The band's cell holding (x, y), -1 off the band; cellPrediction(i) is at() for it. What
     * a caller weighing many points caches per cell. */
    std::int64_t cellIndex(double x, double y) const;
    Prediction cellPrediction(std::int64_t i) const;

    /** The centres of the band's cells (n x 2): where a particle may start. */
    Eigen::MatrixX2d cellCentres() const;
    std::size_t cells() const { return cells_.size(); }
    double cellSize() const { return params_.cell; }
    const GpHyperparameters& hyperparameters() const { return h_; }
    const Eigen::Vector3f& priorMean() const { return prior_mean_; }
    float priorVariance() const { return prior_variance_; }

  private:
    static std::uint64_t key(std::int64_t ix, std::int64_t iy);
    std::int64_t index(double v) const;

    struct Cell {
        Eigen::Vector3f mean;
        float variance;
    };
    Params params_;
    GpHyperparameters h_;
    Eigen::Vector3f prior_mean_;
    float prior_variance_{0};
    std::unordered_map<std::uint64_t, std::uint32_t> index_;
    // The same as a dense raster over the band's bounding box, when that is not too large: a
    // lookup is then one load instead of a hash probe (the particle filter's hot path).
    std::vector<std::int32_t> dense_;
    std::int64_t dense_x0_{0}, dense_y0_{0}, dense_nx_{0}, dense_ny_{0};
    std::vector<Cell> cells_;
    std::vector<std::pair<std::int64_t, std::int64_t>> cell_ij_;
};

}  // namespace lodestone::magnetic
