#include <gtest/gtest.h>
#include <lodestone/sim/MagneticField.h>

#include <cmath>

using namespace lodestone::sim;

namespace {
// Central-difference Jacobian dB_i/dx_j [uT/m].
Eigen::Matrix3d jacobian(const MagneticField& f, const Eigen::Vector3d& p, double h = 1e-5) {
    Eigen::Matrix3d J;
    for (int j = 0; j < 3; ++j) {
        Eigen::Vector3d d = Eigen::Vector3d::Zero();
        d[j] = h;
        J.col(j) = (f.at(p + d) - f.at(p - d)) / (2 * h);
    }
    return J;
}
}  // namespace

TEST(MagneticField, SingleDipoleMatchesTheTextbookField) {
    MagneticField f;
    const Eigen::Vector3d m(0, 0, 10);  // [A m^2], along +z
    f.addDipole({{1, 2, -0.5}, m});
    // On the axis, B = mu0/(4 pi) 2 m / r^3; in the equatorial plane, -mu0/(4 pi) m / r^3.
    const double r = 0.8, k = 1e-7 * 1e6;  // mu0/(4 pi) in uT m / A
    EXPECT_NEAR(f.at({1, 2, -0.5 + r}).z(), k * 2 * 10 / (r * r * r), 1e-9);
    EXPECT_NEAR(f.at({1, 2, -0.5 + r}).head<2>().norm(), 0.0, 1e-12);
    EXPECT_NEAR(f.at({1 + r, 2, -0.5}).z(), -k * 10 / (r * r * r), 1e-9);
    // Anywhere: the general formula evaluated independently.
    const Eigen::Vector3d p(1.3, 1.6, 0.2), d = p - Eigen::Vector3d(1, 2, -0.5);
    const Eigen::Vector3d n = d.normalized();
    const Eigen::Vector3d expected = k * (3 * n * n.dot(m) - m) / std::pow(d.norm(), 3);
    EXPECT_LT((f.at(p) - expected).norm(), 1e-12);
}

TEST(MagneticField, EarthFieldFromInclinationAndDeclination) {
    MagneticField f;
    f.setEarthField(50, 60 * M_PI / 180, 90 * M_PI / 180);
    EXPECT_NEAR(f.at({0, 0, 0}).norm(), 50, 1e-12);
    EXPECT_NEAR(f.at({0, 0, 0}).x(), 0, 1e-12);
    EXPECT_NEAR(f.at({0, 0, 0}).y(), 25, 1e-12);  // horizontal 50 cos 60, towards +y
    EXPECT_NEAR(f.at({0, 0, 0}).z(), -50 * std::sin(60 * M_PI / 180), 1e-12);  // pointing down
}

TEST(MagneticField, SumOfSourcesIsContinuousCurlFreeAndDivergenceFree) {
    MagneticField f;
    f.setEarthField(50, 1.0, 0.3);
    f.addDipole({{0.5, 0.5, -0.2}, {3, -2, 8}});
    f.addDipole({{-1, 0.2, 1.0}, {-5, 1, 0}});
    f.addLine({-2, -1, -0.3}, {3, -1, -0.3}, {0, 4, -3}, 0.1);
    for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0.3), Eigen::Vector3d(1.2, -0.4, 0.3),
                                     Eigen::Vector3d(-0.7, 0.9, 0.5)}) {
        const Eigen::Matrix3d J = jacobian(f, p);
        const double scale = J.norm();
        ASSERT_GT(scale, 1.0);  // a field that varies, so the checks below mean something
        EXPECT_LT(std::abs(J.trace()) / scale, 1e-5) << "divergence at " << p.transpose();
        const Eigen::Vector3d curl(J(2, 1) - J(1, 2), J(0, 2) - J(2, 0), J(1, 0) - J(0, 1));
        EXPECT_LT(curl.norm() / scale, 1e-5) << "curl at " << p.transpose();
        // Continuity: a millimetre step changes the field by about J * step, no jumps.
        const Eigen::Vector3d step(1e-3, -1e-3, 0.5e-3);
        EXPECT_LT((f.at(p + step) - f.at(p) - J * step).norm(), 1e-4 * scale);
    }
}

TEST(MagneticField, LineIsAChainOfDipolesWithTheGivenMoment) {
    MagneticField f;
    f.addLine({0, 0, 0}, {2, 0, 0}, {0, 0, 5}, 0.1);
    ASSERT_EQ(f.dipoles().size(), 20u);
    Eigen::Vector3d total = Eigen::Vector3d::Zero();
    for (const auto& d : f.dipoles()) total += d.moment;
    EXPECT_NEAR(total.z(), 10.0, 1e-12);  // 5 A m^2/m over 2 m
}
