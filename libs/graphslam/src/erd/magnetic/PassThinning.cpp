#include <lodestone/graphslam/erd/magnetic/PassThinning.h>

#include <cmath>
#include <nanoflann.hpp>

namespace lodestone::graphslam::closure {

namespace {
/** nanoflann's view of the kept readings: their places, by the order they were kept. */
struct KeptReadings {
    const std::vector<PlacedReading>& readings;
    std::vector<std::size_t> ids;
    std::size_t kdtree_get_point_count() const { return ids.size(); }
    double kdtree_get_pt(std::size_t k, std::size_t d) const {
        return readings[ids[k]].at[static_cast<Eigen::Index>(d)];
    }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
        return false;
    }
};
}  // namespace

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
    // The kept readings, indexed as they come (nanoflann's dynamic k-d tree over them).
    KeptReadings kept{readings, {}};
    using Tree = nanoflann::KDTreeSingleIndexDynamicAdaptor<
        nanoflann::L2_Simple_Adaptor<double, KeptReadings>, KeptReadings, -1, std::size_t>;
    Tree tree(2, kept, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    std::vector<std::pair<std::size_t, double>> found;
    const auto held = [&](std::size_t i) {
        found.clear();
        // (a hair wider than the radius: nanoflann keeps distances below it, near() decides)
        nanoflann::RadiusResultSet<double, std::size_t> near2(radius * radius * (1 + 1e-9), found);
        tree.findNeighbors(near2, readings[i].at.data(), nanoflann::SearchParams());
        for (const auto& hit : found) {
            const std::size_t k = kept.ids[hit.first];
            const auto &a = readings[i], &b = readings[k];
            const bool anotherPass = a.segment != b.segment || std::abs(a.s - b.s) >= minTravelGap;
            if (anotherPass && sameFrame(a.segment, b.segment) && near(i, k, radius) &&
                together(i, k))
                return true;
        }
        return false;
    };
    for (std::size_t i = 0; i < count; ++i) {
        if (!whole(i)) continue;
        if (held(i)) {
            redundant[i] = 1;
        } else {
            kept.ids.push_back(i);
            tree.addPoints(kept.ids.size() - 1, kept.ids.size() - 1);
        }
    }
    return redundant;
}

}  // namespace lodestone::graphslam::closure
