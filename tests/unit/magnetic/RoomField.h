// A synthetic room whose field is known everywhere, and a map of it made by mowing the room:
// shared by the tests of the field map over the floor and of what localizes in it.
#pragma once

#include <lodestone/magnetic/PlanarFieldGrid.h>

#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

namespace lodestone::testing {

/** A room's field: the earth's plus Gaussian bumps of up to `amplitude` uT a few decimetres
 * wide, scattered over a `size` m square by a seed (each component its own). */
class RoomField {
  public:
    RoomField(unsigned seed, double size, double amplitude) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> where(-1, size + 1), value(-amplitude, amplitude),
            width(0.2, 0.5);
        for (int k = 0; k < static_cast<int>(size * size * 3); ++k) {
            bumps_.push_back({where(rng), where(rng), width(rng),
                              Eigen::Vector3d(value(rng), value(rng), value(rng))});
        }
    }
    Eigen::Vector3d at(double x, double y) const {
        Eigen::Vector3d b(20, 0, -40);
        for (const auto& k : bumps_) {
            const double d2 = (x - k.x) * (x - k.x) + (y - k.y) * (y - k.y);
            b += k.v * std::exp(-0.5 * d2 / (k.w * k.w));
        }
        return b;
    }

  private:
    struct Bump {
        double x, y, w;
        Eigen::Vector3d v;
    };
    std::vector<Bump> bumps_;
};

inline magnetic::GpHyperparameters roomHyperparameters() {
    magnetic::GpHyperparameters h;
    h.sigmaF = 5.0;
    h.lengthScale = 0.3;
    h.sigmaN = 0.5;
    return h;
}

/** Readings every 0.02 m along lines y = 0, 0.5, ... across a 4 m square (a mapping run
 * mowing the room), with reading noise 0.5 uT. */
inline std::shared_ptr<magnetic::PlanarFieldGrid> mowedMap(const RoomField& field,
                                                           unsigned seed = 7) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, 0.5);
    std::vector<Eigen::Vector2d> p;
    std::vector<Eigen::Vector3d> f;
    for (double y = 0; y <= 4.0; y += 0.5) {
        for (double x = 0; x <= 4.0; x += 0.02) {
            p.emplace_back(x, y);
            f.push_back(field.at(x, y) + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
        }
    }
    Eigen::MatrixX2d P(static_cast<Eigen::Index>(p.size()), 2);
    Eigen::MatrixX3d F(static_cast<Eigen::Index>(p.size()), 3);
    for (std::size_t i = 0; i < p.size(); ++i) {
        P.row(static_cast<Eigen::Index>(i)) = p[i].transpose();
        F.row(static_cast<Eigen::Index>(i)) = f[i].transpose();
    }
    return std::make_shared<magnetic::PlanarFieldGrid>(P, F, roomHyperparameters());
}

}  // namespace lodestone::testing
