#include <lodestone/graphslam/erd/magnetic/PassThinning.h>

#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace lodestone::graphslam::closure {

std::vector<char> redundantReadings(const std::vector<PlacedReading>& readings, std::size_t reach,
                                    double radius, double minTravelGap,
                                    const std::function<bool(int, int)>& sameFrame) {
    const std::size_t count = readings.size();
    std::vector<char> redundant(count, 0);
    if (!(radius > 0)) return redundant;
    const auto whole = [&](std::size_t i) {
        return i >= reach && i + reach < count &&
               readings[i - reach].segment == readings[i].segment &&
               readings[i + reach].segment == readings[i].segment;
    };
    const auto near = [&](std::size_t a, std::size_t b, double d) {
        return (readings[a].at - readings[b].at).norm() <= d;
    };
    const auto together = [&](std::size_t i, std::size_t k) {
        const double ends = 2 * radius;
        return (near(k - reach, i - reach, ends) && near(k + reach, i + reach, ends)) ||
               (near(k + reach, i - reach, ends) && near(k - reach, i + reach, ends));
    };
    // Kept readings by grid cell of the radius: a neighbour within it is in the 3 x 3 cells.
    std::unordered_map<std::int64_t, std::vector<std::size_t>> kept;
    const auto cell = [&](const Eigen::Vector2d& p, int dx, int dy) {
        const auto x = static_cast<std::int64_t>(std::floor(p.x() / radius)) + dx;
        const auto y = static_cast<std::int64_t>(std::floor(p.y() / radius)) + dy;
        return (x << 32) ^ (y & 0xffffffff);
    };
    const auto held = [&](std::size_t i) {
        for (int dx = -1; dx <= 1; ++dx) {
            for (int dy = -1; dy <= 1; ++dy) {
                const auto found = kept.find(cell(readings[i].at, dx, dy));
                if (found == kept.end()) continue;
                for (const std::size_t k : found->second) {
                    const auto &a = readings[i], &b = readings[k];
                    const bool anotherPass =
                        a.segment != b.segment || std::abs(a.s - b.s) >= minTravelGap;
                    if (anotherPass && sameFrame(a.segment, b.segment) && near(i, k, radius) &&
                        together(i, k))
                        return true;
                }
            }
        }
        return false;
    };
    for (std::size_t i = 0; i < count; ++i) {
        if (!whole(i)) continue;
        if (held(i)) {
            redundant[i] = 1;
        } else {
            kept[cell(readings[i].at, 0, 0)].push_back(i);
        }
    }
    return redundant;
}

}  // namespace lodestone::graphslam::closure
