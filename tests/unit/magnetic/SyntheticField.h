#pragma once
// A smooth field along a path for the magnetic tests: the earth's (|B| 50 uT, B_z -40 uT)
// plus Gaussian bumps of a few uT a few decimetres wide, placed by a seed.
#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

namespace lodestone::test {

class SyntheticField {
  public:
    explicit SyntheticField(unsigned seed, double length = 20.0, double amplitude = 5.0) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> where(0, length), size(-amplitude, amplitude),
            width(0.15, 0.5);
        for (int k = 0; k < static_cast<int>(length * 3); ++k) {
            bumps_.push_back({where(rng), size(rng), size(rng), width(rng)});
        }
    }
    /** (|B|, B_z) at travel s [uT]. */
    Eigen::VectorXd at(double s) const {
        Eigen::VectorXd v(2);
        v << 50, -40;
        for (const auto& b : bumps_) {
            const double g = std::exp(-0.5 * (s - b.centre) * (s - b.centre) / (b.width * b.width));
            v[0] += b.magnitude * g;
            v[1] += b.vertical * g;
        }
        return v;
    }

  private:
    struct Bump {
        double centre, magnitude, vertical, width;
    };
    std::vector<Bump> bumps_;
};

}  // namespace lodestone::test
