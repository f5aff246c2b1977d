#pragma once
// Two meshes (or point sets) compared vertex by vertex, for the dense model's tests.

#include <Eigen/Core>

#include <cmath>
#include <map>
#include <tuple>
#include <vector>

namespace lodestone::test {

/** The share of `b`'s points with one of `a`'s within `radius` [m] (a grid of radius-sized
 * cells, each point looked for in its cell and the 26 around it). */
inline double shareWithin(const std::vector<Eigen::Vector3f>& a, const std::vector<Eigen::Vector3f>& b, float radius) {
    const auto cell = [radius](const Eigen::Vector3f& p) {
        return std::make_tuple(int(std::floor(p.x() / radius)), int(std::floor(p.y() / radius)),
                               int(std::floor(p.z() / radius)));
    };
    std::map<std::tuple<int, int, int>, std::vector<Eigen::Vector3f>> grid;
    for (const auto& p : a) grid[cell(p)].push_back(p);
    std::size_t near = 0;
    for (const auto& p : b) {
        const auto [x, y, z] = cell(p);
        bool found = false;
        for (int dx = -1; dx <= 1 && !found; ++dx)
            for (int dy = -1; dy <= 1 && !found; ++dy)
                for (int dz = -1; dz <= 1 && !found; ++dz) {
                    const auto it = grid.find({x + dx, y + dy, z + dz});
                    if (it == grid.end()) continue;
                    for (const auto& q : it->second) found |= (q - p).norm() <= radius;
                }
        near += found;
    }
    return b.empty() ? 0.0 : double(near) / double(b.size());
}

}  // namespace lodestone::test
