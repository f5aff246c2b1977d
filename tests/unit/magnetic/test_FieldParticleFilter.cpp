// The field map over the floor (PlanarFieldGrid) and localization in it from nothing
// (FieldParticleFilter), on a synthetic room whose field is known everywhere.
#include <gtest/gtest.h>
#include <lodestone/magnetic/FieldParticleFilter.h>

#include "RoomField.h"

#include <cmath>
#include <random>
#include <vector>

using lodestone::magnetic::FieldParticleFilter;
using lodestone::magnetic::PlanarFieldGrid;
using lodestone::testing::mowedMap;
using lodestone::testing::roomHyperparameters;
using lodestone::testing::RoomField;

namespace {

struct Walk {
    std::vector<Eigen::Vector3d> poses;  // x, y, yaw every 0.02 m
};

/** A walk across the mowed lines: from (start) heading `yaw`, straight for `length` m. */
Walk straightWalk(const Eigen::Vector2d& start, double yaw, double length) {
    Walk w;
    for (double s = 0; s <= length; s += 0.02) {
        w.poses.emplace_back(start.x() + s * std::cos(yaw), start.y() + s * std::sin(yaw), yaw);
    }
    return w;
}

struct Outcome {
    bool converged{false};
    double travel{0};
    Eigen::Vector3d error{Eigen::Vector3d::Zero()};  // at the end of the walk
};

/** Runs the filter along `walk` with exact odometry (a small covariance declared) and
 * readings of `field` turned into the robot frame. */
Outcome localize(FieldParticleFilter& pf, const RoomField& field, const Walk& walk) {
    Outcome o;
    const Eigen::Matrix3d cov = Eigen::Vector3d(1e-6, 1e-6, 1e-6).asDiagonal();
    for (std::size_t i = 0; i < walk.poses.size(); ++i) {
        const auto& q = walk.poses[i];
        if (i > 0) {
            const auto& p = walk.poses[i - 1];
            const double c = std::cos(p.z()), s = std::sin(p.z());
            const double dx = q.x() - p.x(), dy = q.y() - p.y();
            pf.move({c * dx + s * dy, -s * dx + c * dy, q.z() - p.z()}, cov);
        }
        const Eigen::Vector3d w = field.at(q.x(), q.y());
        const double c = std::cos(q.z()), s = std::sin(q.z());
        pf.measure({c * w.x() + s * w.y(), -s * w.x() + c * w.y(), w.z()});
        if (!o.converged && pf.estimate().converged) {
            o.converged = true;
            o.travel = 0.02 * static_cast<double>(i);
        }
    }
    const auto e = pf.estimate();
    o.error = e.pose - walk.poses.back();
    o.error.z() = std::remainder(o.error.z(), 2 * M_PI);
    return o;
}

FieldParticleFilter::Params filterParams() {
    FieldParticleFilter::Params p;
    p.particles = 40000;
    return p;
}

}  // namespace

TEST(PlanarFieldGrid, PredictsTheFieldNearItsReadingsAndThePriorFarFromThem) {
    const RoomField field(3, 4.0, 6.0);
    const auto map = mowedMap(field);
    double worst = 0;
    for (double x = 0.3; x < 3.8; x += 0.37) {
        for (double y : {0.0, 1.5, 3.0}) {  // on mapped lines
            const auto m = map->at(x, y);
            ASSERT_TRUE(m.known);
            worst = std::max(worst, (m.mean.cast<double>() - field.at(x, y)).cwiseAbs().maxCoeff());
            EXPECT_LT(m.variance, 0.5);
        }
    }
    EXPECT_LT(worst, 1.0);  // the reading noise is 0.5 uT; the cell's centre is 3.5 cm off
    const auto between = map->at(1.0, 0.25);  // 0.25 m from two lines
    EXPECT_TRUE(between.known);
    EXPECT_GT(between.variance, 1.0);
    const auto far = map->at(10.0, 10.0);
    EXPECT_FALSE(far.known);
    EXPECT_FLOAT_EQ(far.variance, 25.0f);
    EXPECT_THROW(
        PlanarFieldGrid(Eigen::MatrixX2d(0, 2), Eigen::MatrixX3d(0, 3), roomHyperparameters()),
        std::invalid_argument);
}

TEST(FieldParticleFilter, FindsAWalkAcrossTheMappedLinesEitherWay) {
    const RoomField field(3, 4.0, 6.0);
    const auto map = mowedMap(field);
    // Across the lines, not along any of them: what the sequence matchers cannot place.
    for (const double yaw : {M_PI / 2 - 0.3, -M_PI / 2 - 0.3}) {
        const Eigen::Vector2d start =
            yaw > 0 ? Eigen::Vector2d(0.6, 0.1) : Eigen::Vector2d(3.4, 4.0);
        FieldParticleFilter pf(map, filterParams());
        const auto o = localize(pf, field, straightWalk(start, yaw, 4.2));
        EXPECT_TRUE(o.converged) << "yaw " << yaw;
        EXPECT_LT(o.travel, 3.5);
        // Lines 0.5 m apart, the field decorrelating over 0.3 m: between them the map is
        // loose, and the cloud's sigma settles at 0.1-0.15 m.
        EXPECT_LT(o.error.head<2>().norm(), 0.15) << o.error.transpose();
        EXPECT_LT(std::abs(o.error.z()), 3 * M_PI / 180);
    }
}

TEST(FieldParticleFilter, NeverConvergesInAFlatField) {
    const RoomField flat(3, 4.0, 0.0);
    const auto map = mowedMap(flat);
    FieldParticleFilter pf(map, filterParams());
    const auto o = localize(pf, flat, straightWalk({0.6, 0.1}, M_PI / 2 - 0.3, 4.2));
    EXPECT_FALSE(o.converged);
}

TEST(FieldParticleFilter, IsDeterministicForASeed) {
    const RoomField field(5, 4.0, 6.0);
    const auto map = mowedMap(field);
    const auto walk = straightWalk({0.5, 0.3}, 1.2, 3.0);
    FieldParticleFilter a(map, filterParams()), b(map, filterParams());
    localize(a, field, walk);
    localize(b, field, walk);
    EXPECT_EQ(a.estimate().pose, b.estimate().pose);
    EXPECT_EQ(a.estimate().covariance, b.estimate().covariance);
}

TEST(PlanarFieldGrid, ALengthScaleBelowHalfACellIsRefusedNotACrash) {
    // (A hyperparameter fit run off to zero: no cell lies within reach of any reading.)
    auto h = lodestone::testing::roomHyperparameters();
    h.lengthScale = 0.001;
    const Eigen::MatrixX2d P = Eigen::MatrixX2d::Zero(3, 2);  // 0.035 m from a cell centre
    const Eigen::MatrixX3d F = Eigen::MatrixX3d::Constant(3, 3, 10.0);
    EXPECT_THROW(PlanarFieldGrid(P, F, h), std::invalid_argument);
}
