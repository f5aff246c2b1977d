#pragma once
// A field over the floor plane for the 2-D magnetic tests: two channels, a constant plus 2-D
// Gaussian bumps (0.25-0.5 m wide unless said) placed by a seed; readings along straight passes.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace lodestone::test {

struct PlaneField {
    explicit PlaneField(unsigned seed, double x0 = -1, double x1 = 5, int count = 60,
                        double w0 = 0.25, double w1 = 0.5) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> x(x0, x1), y(-1.5, 1.5), a(-6, 6), w(w0, w1);
        for (int k = 0; k < count; ++k) bumps.push_back({x(rng), y(rng), a(rng), a(rng), w(rng)});
    }
    Eigen::VectorXd at(const Eigen::Vector2d& p) const {
        Eigen::VectorXd v(2);
        v << 50, -40;
        for (const auto& b : bumps) {
            const double g = std::exp(-0.5 * (std::pow(p.x() - b[0], 2) + std::pow(p.y() - b[1], 2)) /
                                      (b[4] * b[4]));
            v[0] += b[2] * g;
            v[1] += b[3] * g;
        }
        return v;
    }
    std::vector<std::array<double, 5>> bumps;
};

// Readings of `field` along y = `y` for x in [x0, x1) every `step` m.
inline void pass(const PlaneField& field, double y, double x0, double x1,
                 std::vector<Eigen::Vector2d>& at, std::vector<Eigen::VectorXd>& values,
                 double step = 0.05) {
    for (double x = x0; x < x1; x += step) {
        at.emplace_back(x, y);
        values.push_back(field.at(at.back()));
    }
}

inline Eigen::MatrixX2d rowsOf(const std::vector<Eigen::Vector2d>& v) {
    Eigen::MatrixX2d m(static_cast<Eigen::Index>(v.size()), 2);
    for (std::size_t i = 0; i < v.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
    return m;
}
inline Eigen::MatrixXd rowsOf(const std::vector<Eigen::VectorXd>& v) {
    Eigen::MatrixXd m(static_cast<Eigen::Index>(v.size()), v.front().size());
    for (std::size_t i = 0; i < v.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
    return m;
}

}  // namespace lodestone::test
