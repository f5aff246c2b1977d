// A recent stretch of readings placed in a field map near where the graph puts it
// (matchStretch): found where it is, and not found where the map cannot tell.
#include <gtest/gtest.h>
#include <lodestone/magnetic/StretchFieldMatcher.h>

#include <cmath>
#include <random>
#include <vector>

#include "RoomField.h"

using lodestone::magnetic::matchStretch;
using lodestone::magnetic::StretchSample;
using lodestone::testing::mowedMap;
using lodestone::testing::RoomField;

namespace {

/** What a closer asks of a match: a Bayes factor of 1000 (posterior odds of 100:1 where one
 * query in ten is a revisit). */
const double kDecisive = std::log(1000.0);

/** Readings every 0.05 m along a straight line of `length` m ending at `end` (the anchor)
 * and heading `yaw`, in the robot frame and relative to the anchor, with 0.5 uT noise; each
 * counts 0.05 / 0.3 (the room's length scale). */
std::vector<StretchSample> stretchTo(const RoomField& field, const Eigen::Vector3d& end,
                                     double length, unsigned seed = 3) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, 0.5);
    std::vector<StretchSample> out;
    const double c = std::cos(end.z()), s = std::sin(end.z());
    for (double back = length; back >= 0; back -= 0.05) {
        const Eigen::Vector3d world = field.at(end.x() - back * c, end.y() - back * s) +
                                      Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
        StretchSample k;
        k.pose = {-back, 0, 0};
        k.field = {c * world.x() + s * world.y(), -s * world.x() + c * world.y(), world.z()};
        k.weight = 0.05 / 0.3;
        out.push_back(k);
    }
    return out;
}

}  // namespace

TEST(StretchFieldMatcher, PlacesAStretchThatCrossesTheMappedLines) {
    const RoomField field(11, 4.0, 8.0);
    const auto map = mowedMap(field);
    // 3 m across the lines (mapped along x every 0.5 m), ending at (2.2, 3.1) heading 70 deg;
    // the graph has it 0.35 m and 6 deg off.
    const Eigen::Vector3d truth(2.2, 3.1, 70 * M_PI / 180);
    const auto stretch = stretchTo(field, truth, 3.0);
    const Eigen::Vector3d prior = truth + Eigen::Vector3d(0.25, -0.25, 6 * M_PI / 180);
    const auto m = matchStretch(*map, stretch, prior, 0.3 * 0.3 * Eigen::Matrix2d::Identity());
    EXPECT_GT(m.logEvidence, kDecisive);
    EXPECT_LT((m.pose.head<2>() - truth.head<2>()).norm(), 0.08);
    EXPECT_LT(std::abs(m.pose.z() - truth.z()) * 180 / M_PI, 2.0);
    EXPECT_LT(m.positionSigma, 0.15);
    EXPECT_GT(m.support, 1.0);
    // The covariance holds the error it reports (within 3 sigma per axis).
    for (int k = 0; k < 3; ++k)
        EXPECT_LT(std::abs(m.pose(k) - truth(k)), 3 * std::sqrt(m.covariance(k, k)) + 1e-9) << k;
}

TEST(StretchFieldMatcher, AnotherRoomsFieldIsNotDecisive) {
    // Stretches of other rooms' fields (the same earth's field, other anomalies) where the
    // graph puts them on this map: in calm stretches they fit calm places, never decisively.
    const RoomField field(11, 4.0, 8.0);
    const auto map = mowedMap(field);
    for (unsigned seed = 12; seed < 20; ++seed) {
        const RoomField other(seed, 4.0, 8.0);
        for (const double x : {1.0, 2.2, 3.0}) {
            const Eigen::Vector3d at(x, 3.1, 70 * M_PI / 180);
            const auto m = matchStretch(*map, stretchTo(other, at, 3.0), at,
                                        0.3 * 0.3 * Eigen::Matrix2d::Identity());
            EXPECT_LT(m.logEvidence, kDecisive) << seed << " at x = " << x;
        }
    }
}

TEST(StretchFieldMatcher, AFlatFieldMatchesEverywhereAndSoNowhere) {
    // No anomalies: the readings agree with the map at every pose of the gate - the posterior
    // is as wide as the prior, which is what a caller's uniqueness test sees.
    const RoomField field(11, 4.0, 0.0);
    const auto map = mowedMap(field);
    const Eigen::Vector3d truth(2.0, 2.1, 0.0);  // along a mapped line, 0.1 m beside it
    const auto m = matchStretch(*map, stretchTo(field, truth, 3.0), truth,
                                0.3 * 0.3 * Eigen::Matrix2d::Identity());
    EXPECT_GT(m.positionSigma, 0.2);
}

TEST(StretchFieldMatcher, OffTheMapThereIsNothingToWeigh) {
    const RoomField field(11, 4.0, 8.0);
    const auto map = mowedMap(field);
    const Eigen::Vector3d far(20.0, 20.0, 0.0);
    const auto m = matchStretch(*map, stretchTo(field, far, 3.0), far,
                                0.3 * 0.3 * Eigen::Matrix2d::Identity());
    EXPECT_NEAR(m.logEvidence, 0.0, 1e-9);
    EXPECT_EQ(m.support, 0.0);
}
