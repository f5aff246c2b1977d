// closure::redundantReadings: a map's passes of one line kept once (either way), a pass beside
// it, a crossing and the pass's own readings kept, across frames nothing.
#include <gtest/gtest.h>
#include <lodestone/graphslam/erd/magnetic/PassThinning.h>

#include <numeric>

using namespace lodestone;
using graphslam::closure::PlacedReading;

namespace {

/** Readings every 0.05 m from `a` to `b` in `segment`, travel going on (a new segment: a pass
 * of its own, the way a map's sessions are). */
void pass(std::vector<PlacedReading>& out, Eigen::Vector2d a, Eigen::Vector2d b, int segment) {
    const bool goesOn = !out.empty() && out.back().segment == segment;
    const double s0 = out.empty() ? 0 : out.back().s + (goesOn ? 0 : 5);
    const int n = static_cast<int>(std::lround((b - a).norm() / 0.05));
    for (int k = goesOn ? 1 : 0; k <= n; ++k)
        out.push_back({a + (b - a) * (double(k) / n), s0 + 0.05 * k, segment});
}

std::size_t redundantIn(const std::vector<char>& r, std::size_t from, std::size_t to) {
    return std::accumulate(r.begin() + long(from), r.begin() + long(to), std::size_t{0});
}

const auto kOneFrame = [](int, int) { return true; };

}  // namespace

TEST(PassThinning, ALineWalkedAgainEitherWayIsHeldOnce) {
    std::vector<PlacedReading> r;
    pass(r, {0, 0}, {10, 0}, 0);  // the first pass: kept
    const std::size_t again = r.size();
    pass(r, {0, 0.04}, {10, 0.04}, 1);  // the same line, 4 cm over
    const std::size_t back = r.size();
    pass(r, {10, -0.03}, {0, -0.03}, 2);  // walked back
    const std::size_t beside = r.size();
    pass(r, {0, 0.3}, {10, 0.3}, 3);  // 0.3 m beside: another line
    const std::size_t crossing = r.size();
    pass(r, {5, -5}, {5, 5}, 4);  // across them all
    const std::size_t end = r.size();
    const std::size_t reach = 39;  // a 2 m window of 0.05 m readings
    const auto red = graphslam::closure::redundantReadings(r, reach, 0.1, 4.0, kOneFrame);
    ASSERT_EQ(red.size(), r.size());
    EXPECT_EQ(redundantIn(red, 0, again), 0u);
    // Every reading of the second and returning pass whose windows are whole in the pass.
    EXPECT_EQ(redundantIn(red, again, back), back - again - 2 * reach);
    EXPECT_EQ(redundantIn(red, back, beside), beside - back - 2 * reach);
    EXPECT_EQ(redundantIn(red, beside, crossing), 0u);
    EXPECT_EQ(redundantIn(red, crossing, end), 0u);
}

TEST(PassThinning, PassesThatPartAreKeptWhereTheyPart) {
    // The second pass follows the first for 5 m, then bends away: near the bend its windows
    // leave the first pass's line, and those readings stay.
    std::vector<PlacedReading> r;
    pass(r, {0, 0}, {10, 0}, 0);
    const std::size_t second = r.size();
    pass(r, {0, 0}, {5, 0}, 1);
    pass(r, {5, 0}, {5, 5}, 1);
    const auto red = graphslam::closure::redundantReadings(r, 39, 0.1, 4.0, kOneFrame);
    for (std::size_t i = second; i < r.size(); ++i) {
        if (!red[i]) continue;
        EXPECT_LT(r[i].at.x(), 5 - 1.5) << i;  // 2 m ahead of it the pass is still on the line
        EXPECT_NEAR(r[i].at.y(), 0, 1e-9) << i;
    }
    EXPECT_GT(redundantIn(red, second, r.size()), 20u);
}

TEST(PassThinning, NothingIsHeldAcrossFramesOrWithinOnePass) {
    std::vector<PlacedReading> r;
    pass(r, {0, 0}, {10, 0}, 0);
    pass(r, {0, 0}, {10, 0}, 1);  // a segment that never joined the first
    const auto apart =
        graphslam::closure::redundantReadings(r, 39, 0.1, 4.0, [](int a, int b) { return a == b; });
    EXPECT_EQ(redundantIn(apart, 0, r.size()), 0u);
    const auto joined = graphslam::closure::redundantReadings(r, 39, 0.1, 4.0, kOneFrame);
    EXPECT_GT(redundantIn(joined, 0, r.size()), 100u);
    // One slow pass (readings 1 cm apart): its own earlier readings are no other pass.
    std::vector<PlacedReading> slow;
    for (int k = 0; k <= 1000; ++k) slow.push_back({{0.01 * k, 0}, 0.01 * k, 0});
    EXPECT_EQ(redundantIn(graphslam::closure::redundantReadings(slow, 39, 0.1, 4.0, kOneFrame), 0,
                          slow.size()),
              0u);
    // Radius 0: thinning off.
    EXPECT_EQ(
        redundantIn(graphslam::closure::redundantReadings(r, 39, 0, 4.0, kOneFrame), 0, r.size()),
        0u);
}
