#include <gtest/gtest.h>
#include <lodestone/odometry/DiffDriveOdometry.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <Eigen/Dense>
#include <cmath>
#include <utility>
#include <vector>

using lodestone::odometry::DiffDriveOdometry;

namespace {
DiffDriveOdometry::Params params() {
    DiffDriveOdometry::Params p;
    p.wheelBase = 0.25;
    p.wheelRadius = 0.04;
    p.ticksPerRev = 1000;
    p.wheelNoise = 1e-3;
    return p;
}
}  // namespace

TEST(DiffDriveOdometry, StraightAndTurningOnTheSpotFollowEquationOne) {
    DiffDriveOdometry odo(params());
    odo.addTravel(0.5, 0.5);
    EXPECT_NEAR(odo.pose().mean.x(), 0.5, 1e-12);
    EXPECT_NEAR(odo.pose().mean.y(), 0.0, 1e-12);
    odo.addTravel(-0.1, 0.1);  // turn left in place by 0.2 / b
    EXPECT_NEAR(odo.pose().mean.phi(), 0.2 / 0.25, 1e-12);
    EXPECT_NEAR(odo.pose().mean.x(), 0.5, 1e-12);
    // Eq. (1) for a general step: heading at the middle of the step.
    const auto step = DiffDriveOdometry::stepFromOrigin(0.30, 0.34, params());
    const double ds = 0.32, dphi = 0.04 / 0.25;
    EXPECT_NEAR(step.mean.x(), ds * std::cos(dphi / 2), 1e-12);
    EXPECT_NEAR(step.mean.y(), ds * std::sin(dphi / 2), 1e-12);
    EXPECT_NEAR(step.mean.phi(), dphi, 1e-12);
}

TEST(DiffDriveOdometry, SmallStepsTraceACircleArc) {
    DiffDriveOdometry odo(params());
    // Right wheel 10 % faster: radius R = b/2 (r + l)/(r - l).
    const double l = 0.001, r = 0.0011, R = 0.25 / 2 * (r + l) / (r - l);
    for (int i = 0; i < 2000; ++i) odo.addTravel(l, r);
    const double phi = 2000 * (r - l) / 0.25;
    EXPECT_NEAR(odo.pose().mean.x(), R * std::sin(phi), 1e-6);
    EXPECT_NEAR(odo.pose().mean.y(), R * (1 - std::cos(phi)), 1e-6);
}

TEST(DiffDriveOdometry, CovarianceJacobianMatchesNumericalDerivatives) {
    const auto p = params();
    const double dl = 0.21, dr = 0.27, h = 1e-7;
    const auto f = [&](double l, double r) {
        const auto m = DiffDriveOdometry::stepFromOrigin(l, r, p).mean;
        return Eigen::Vector3d(m.x(), m.y(), m.phi());
    };
    Eigen::Matrix<double, 3, 2> G;
    G.col(0) = (f(dl, dr + h) - f(dl, dr - h)) / (2 * h);  // d/d(Δs_r)
    G.col(1) = (f(dl + h, dr) - f(dl - h, dr)) / (2 * h);  // d/d(Δs_l)
    const Eigen::Matrix2d Q = Eigen::Vector2d(p.wheelNoise * dr, p.wheelNoise * dl).asDiagonal();
    const Eigen::Matrix3d expected = G * Q * G.transpose();
    const auto step = DiffDriveOdometry::stepFromOrigin(dl, dr, p);
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(step.cov(i, j), expected(i, j), 1e-12) << i << j;
    }
}

TEST(DiffDriveOdometry, ScaleJacobiansMatchNumericalDerivatives) {
    const auto p = params();
    const double h = 1e-7;
    const auto pose = [](const mrpt::poses::CPose2D& m) {
        return Eigen::Vector3d(m.x(), m.y(), m.phi());
    };
    // One step: its motion with the left and right travels scaled by 1 + e.
    const double dl = 0.21, dr = 0.27;
    const auto step = [&](double el, double er) {
        return pose(DiffDriveOdometry::stepFromOrigin(dl * (1 + el), dr * (1 + er), p).mean);
    };
    Eigen::Matrix<double, 3, 2> numeric;
    numeric.col(0) = (step(h, 0) - step(-h, 0)) / (2 * h);
    numeric.col(1) = (step(0, h) - step(0, -h)) / (2 * h);
    EXPECT_LT((DiffDriveOdometry::scaleJacobian(dl, dr, p) - numeric).cwiseAbs().maxCoeff(), 1e-7);

    // A turning chain of steps: the composed Jacobian against the chain re-run with the
    // scales applied to every step (an edge's worth of frames).
    const std::vector<std::pair<double, double>> steps{
        {0.01, 0.012}, {0.011, 0.009}, {-0.02, 0.02}, {0.015, 0.015}, {0.013, 0.016}};
    const auto chain = [&](double el, double er) {
        mrpt::poses::CPose2D m;
        for (const auto& [l, r] : steps)
            m = m + DiffDriveOdometry::stepFromOrigin(l * (1 + el), r * (1 + er), p).mean;
        return pose(m);
    };
    mrpt::poses::CPose2D composed;
    Eigen::Matrix<double, 3, 2> J = Eigen::Matrix<double, 3, 2>::Zero();
    for (const auto& [l, r] : steps) {
        const auto m = DiffDriveOdometry::stepFromOrigin(l, r, p).mean;
        J = DiffDriveOdometry::composeScaleJacobian(composed, J, m,
                                                    DiffDriveOdometry::scaleJacobian(l, r, p));
        composed = composed + m;
    }
    numeric.col(0) = (chain(h, 0) - chain(-h, 0)) / (2 * h);
    numeric.col(1) = (chain(0, h) - chain(0, -h)) / (2 * h);
    EXPECT_LT((J - numeric).cwiseAbs().maxCoeff(), 1e-7);
    EXPECT_GT(J.cwiseAbs().maxCoeff(), 1e-3) << "a chain that turns responds to its scales";
}

TEST(DiffDriveOdometry, UncertaintyGrowsWithDistance) {
    DiffDriveOdometry odo(params());
    double lastTrace = 0;
    for (int i = 0; i < 50; ++i) {
        odo.addTravel(0.02, 0.021);
        const auto& c = odo.pose().cov;
        EXPECT_GT(c.trace(), lastTrace);
        lastTrace = c.trace();
        EXPECT_NEAR(c(0, 1), c(1, 0), 1e-15);
        EXPECT_GE(c.asEigen().determinant(), -1e-20);
    }
    // Lateral uncertainty grows faster than along-track as heading errors accumulate.
    EXPECT_GT(odo.pose().cov(1, 1), 0.0);
}

TEST(DiffDriveOdometry, TicksWithCounterWrapAround) {
    DiffDriveOdometry odo(params());
    const std::int32_t nearMax = 2147483000;
    EXPECT_FALSE(odo.addTicks(nearMax, nearMax));  // first reading: reference only
    // 1000 ticks later both counters have wrapped past INT32_MAX.
    const auto inc = odo.addTicks(static_cast<std::int32_t>(nearMax + 1000u),
                                  static_cast<std::int32_t>(nearMax + 1000u));
    ASSERT_TRUE(inc);
    EXPECT_NEAR(inc->leftTravel, 2 * M_PI * 0.04, 1e-12);  // one revolution
    EXPECT_NEAR(odo.pose().mean.x(), 2 * M_PI * 0.04, 1e-12);
}

TEST(DiffDriveOdometry, ParamsLoadStrictlyFromIni) {
    mrpt::config::CConfigFileMemory ini("[wheels]\nwheel_base = 0.3\nwheel_radius = 0.05\n");
    DiffDriveOdometry::Params p;
    p.loadFromConfigFile(ini, "wheels");
    EXPECT_DOUBLE_EQ(p.wheelBase, 0.3);
    EXPECT_DOUBLE_EQ(p.wheelRadius, 0.05);
    EXPECT_DOUBLE_EQ(p.ticksPerRev, DiffDriveOdometry::Params().ticksPerRev);  // default kept
    mrpt::config::CConfigFileMemory typo("[wheels]\nwheel_bas = 0.3\n");
    EXPECT_THROW(p.loadFromConfigFile(typo, "wheels"), std::runtime_error);
}
