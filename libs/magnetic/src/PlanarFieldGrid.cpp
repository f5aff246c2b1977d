#include <lodestone/magnetic/PlanarFieldGrid.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <nanoflann.hpp>
#include <stdexcept>
#include <string>

namespace lodestone::magnetic {

namespace {
/** nanoflann's view of the readings' positions. */
struct Positions {
    const Eigen::MatrixX2d* p;
    std::size_t kdtree_get_point_count() const { return static_cast<std::size_t>(p->rows()); }
    double kdtree_get_pt(std::size_t i, std::size_t d) const {
        return (*p)(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(d));
    }
    template <class BBox>
    bool kdtree_get_bbox(BBox&) const {
        return false;
    }
};
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Positions>,
                                                 Positions, 2>;
}  // namespace

std::uint64_t PlanarFieldGrid::key(std::int64_t ix, std::int64_t iy) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(ix)) << 32) |
           static_cast<std::uint32_t>(iy);
}

std::int64_t PlanarFieldGrid::index(double v) const {
    return static_cast<std::int64_t>(std::floor(v / params_.cell));
}

PlanarFieldGrid::PlanarFieldGrid(const Eigen::MatrixX2d& points, const Eigen::MatrixX3d& field,
                                 const GpHyperparameters& h, const Params& p)
    : params_(p), h_(h) {
    if (points.rows() == 0 || points.rows() != field.rows())
        throw std::invalid_argument("PlanarFieldGrid: empty or mismatched readings");
    if (!points.allFinite() || !field.allFinite())
        throw std::invalid_argument("PlanarFieldGrid: a reading or position is not finite");
    if (!h.valid() || !(p.cell > 0) || !(p.reachScales > 0) || p.neighbours == 0)
        throw std::invalid_argument("PlanarFieldGrid: hyperparameters and grid must be > 0");
    prior_mean_ = field.colwise().mean().cast<float>();
    const double f2 = h.sigmaF * h.sigmaF, inv2l2 = 0.5 / (h.lengthScale * h.lengthScale);
    prior_variance_ = static_cast<float>(f2);

    // The band: every cell whose centre lies within reach of a reading.
    const double reach = p.reachScales * h.lengthScale;
    const auto r = static_cast<std::int64_t>(std::ceil(reach / p.cell));
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
        const std::int64_t cx = index(points(i, 0)), cy = index(points(i, 1));
        for (std::int64_t dx = -r; dx <= r; ++dx) {
            for (std::int64_t dy = -r; dy <= r; ++dy) {
                const double ex = (cx + dx + 0.5) * p.cell - points(i, 0),
                             ey = (cy + dy + 0.5) * p.cell - points(i, 1);
                if (ex * ex + ey * ey > reach * reach) continue;
                const auto [it, added] = index_.emplace(
                    key(cx + dx, cy + dy), static_cast<std::uint32_t>(cell_ij_.size()));
                if (!added) continue;
                cell_ij_.emplace_back(cx + dx, cy + dy);
                if (cell_ij_.size() > p.maxCells)
                    throw std::invalid_argument("PlanarFieldGrid: the band needs more than " +
                                                std::to_string(p.maxCells) + " cells");
            }
        }
    }

    if (cell_ij_.empty())  // a reach below half a cell: nothing to hold the field
        throw std::invalid_argument("PlanarFieldGrid: no cell within reach of a reading");

    // Each cell: a GP on its nearest readings.
    Positions positions{&points};
    Tree tree(2, positions, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    tree.buildIndex();
    const std::size_t k =
        std::min<std::size_t>(p.neighbours, static_cast<std::size_t>(points.rows()));
    std::vector<std::size_t> idx(k);
    std::vector<double> dist(k);
    Eigen::MatrixXd K(k, k);
    Eigen::VectorXd ks(k);
    Eigen::MatrixXd Y(k, 3);
    const Eigen::RowVector3d mu = prior_mean_.cast<double>().transpose();
    cells_.resize(cell_ij_.size());
    for (std::size_t c = 0; c < cell_ij_.size(); ++c) {
        const double q[2] = {(cell_ij_[c].first + 0.5) * p.cell,
                             (cell_ij_[c].second + 0.5) * p.cell};
        nanoflann::KNNResultSet<double> result(k);
        result.init(idx.data(), dist.data());
        tree.findNeighbors(result, q, nanoflann::SearchParams());
        for (std::size_t a = 0; a < k; ++a) {
            const auto ia = static_cast<Eigen::Index>(idx[a]);
            ks[a] = f2 * std::exp(-dist[a] * inv2l2);
            Y.row(a) = field.row(ia) - mu;
            for (std::size_t b = 0; b <= a; ++b) {
                const auto ib = static_cast<Eigen::Index>(idx[b]);
                K(a, b) = K(b, a) =
                    f2 * std::exp(-(points.row(ia) - points.row(ib)).squaredNorm() * inv2l2);
            }
            K(a, a) += h.sigmaN * h.sigmaN;
        }
        const Eigen::LLT<Eigen::MatrixXd> llt(K);
        const Eigen::VectorXd w = llt.solve(ks);
        cells_[c].mean = (mu + w.transpose() * Y).transpose().cast<float>();
        cells_[c].variance = static_cast<float>(std::max(0.0, f2 - ks.dot(w)));
    }

    std::int64_t x0 = cell_ij_.front().first, x1 = x0, y0 = cell_ij_.front().second, y1 = y0;
    for (const auto& [ix, iy] : cell_ij_) {
        x0 = std::min(x0, ix);
        x1 = std::max(x1, ix);
        y0 = std::min(y0, iy);
        y1 = std::max(y1, iy);
    }
    constexpr std::int64_t kMaxDense = 32'000'000;  // 128 MB of indices
    if ((x1 - x0 + 1) * (y1 - y0 + 1) <= kMaxDense) {
        dense_x0_ = x0;
        dense_y0_ = y0;
        dense_nx_ = x1 - x0 + 1;
        dense_ny_ = y1 - y0 + 1;
        dense_.assign(static_cast<std::size_t>(dense_nx_ * dense_ny_), -1);
        for (std::size_t c = 0; c < cell_ij_.size(); ++c)
            dense_[static_cast<std::size_t>((cell_ij_[c].second - y0) * dense_nx_ +
                                            cell_ij_[c].first - x0)] = static_cast<std::int32_t>(c);
        index_ = {};  // the raster answers every lookup: the hash was only the build's
    }
}

std::int64_t PlanarFieldGrid::cellIndex(double x, double y) const {
    const std::int64_t ix = index(x), iy = index(y);
    if (!dense_.empty()) {
        const std::int64_t dx = ix - dense_x0_, dy = iy - dense_y0_;
        if (dx < 0 || dy < 0 || dx >= dense_nx_ || dy >= dense_ny_) return -1;
        return dense_[static_cast<std::size_t>(dy * dense_nx_ + dx)];
    }
    const auto it = index_.find(key(ix, iy));
    return it == index_.end() ? -1 : static_cast<std::int64_t>(it->second);
}

PlanarFieldGrid::Prediction PlanarFieldGrid::cellPrediction(std::int64_t i) const {
    if (i < 0) return {prior_mean_, prior_variance_, false};
    const Cell& c = cells_[static_cast<std::size_t>(i)];
    return {c.mean, c.variance, true};
}

PlanarFieldGrid::Prediction PlanarFieldGrid::at(double x, double y) const {
    return cellPrediction(cellIndex(x, y));
}

Eigen::MatrixX2d PlanarFieldGrid::cellCentres() const {
    Eigen::MatrixX2d out(static_cast<Eigen::Index>(cell_ij_.size()), 2);
    for (std::size_t c = 0; c < cell_ij_.size(); ++c) {
        out(static_cast<Eigen::Index>(c), 0) = (cell_ij_[c].first + 0.5) * params_.cell;
        out(static_cast<Eigen::Index>(c), 1) = (cell_ij_[c].second + 0.5) * params_.cell;
    }
    return out;
}

}  // namespace lodestone::magnetic
