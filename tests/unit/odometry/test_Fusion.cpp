#include <gtest/gtest.h>
#include <lodestone/odometry/CovarianceWeightedFusion.h>
#include <lodestone/odometry/KalmanFusion.h>
#include <lodestone/odometry/PlanarFusion.h>

#include <Eigen/Dense>

using namespace lodestone::odometry;

namespace {
mrpt::poses::CPosePDFGaussian gaussian(double x, double y, double phi, double var) {
    mrpt::poses::CPosePDFGaussian g;
    g.mean = mrpt::poses::CPose2D(x, y, phi);
    g.cov.setIdentity();
    g.cov *= var;
    return g;
}
}  // namespace

TEST(CovarianceWeightedFusion, CombinesByInformation) {
    const auto equal = CovarianceWeightedFusion::combine(gaussian(0.10, 0, 0.02, 1e-4),
                                                         gaussian(0.12, 0, 0.00, 1e-4));
    EXPECT_NEAR(equal.mean.x(), 0.11, 1e-9);
    EXPECT_NEAR(equal.mean.phi(), 0.01, 1e-9);
    EXPECT_NEAR(equal.cov(0, 0), 0.5e-4, 1e-12);  // two equal measurements halve the variance
    const auto lopsided =
        CovarianceWeightedFusion::combine(gaussian(0.10, 0, 0, 1e-2), gaussian(0.12, 0, 0, 1e-6));
    EXPECT_NEAR(lopsided.mean.x(), 0.12, 1e-5);  // the certain one wins
    // Headings either side of +-pi are averaged across it, not through 0.
    const auto wrap = CovarianceWeightedFusion::combine(gaussian(0, 0, M_PI - 0.01, 1e-4),
                                                        gaussian(0, 0, -M_PI + 0.01, 1e-4));
    EXPECT_NEAR(std::abs(wrap.mean.phi()), M_PI, 1e-9);
}

TEST(PlanarFusion, WithoutVisualEveryMethodButVisualFollowsTheWheels) {
    for (const char* method : {"wheel", "covariance", "kalman", "visual"}) {
        auto f = makePlanarFusion(method);
        f->reset({});
        for (int i = 0; i < 100; ++i) {
            OdometryStep s;
            s.wheel = gaussian(0.01, 0, 0.002, 1e-6);
            s.dt = 0.033;
            f->step(s);
        }
        const auto& p = f->pose().mean;
        if (std::string(method) == "visual") {
            EXPECT_NEAR(p.x(), 0.0, 1e-12) << method;  // no VO, no motion
        } else {
            // 100 steps of 1 cm turning 0.2 rad in all: an arc of radius 5 m.
            EXPECT_NEAR(p.phi(), 0.2, 0.02) << method;
            EXPECT_NEAR(p.x(), 5 * std::sin(0.2), 0.02) << method;
        }
    }
    EXPECT_THROW(makePlanarFusion("average"), std::invalid_argument);
}

TEST(PlanarFusion, AgreeingSourcesGiveTheSameMotionAndVisualCorrectsASlippingWheel) {
    auto cov = makePlanarFusion("covariance");
    auto kalman = makePlanarFusion("kalman");
    cov->reset({});
    kalman->reset({});
    for (int i = 0; i < 200; ++i) {
        OdometryStep s;
        s.dt = 0.033;
        s.wheel = gaussian(0.012, 0, 0, 1e-5);   // slips: 20 % too far, and uncertain
        s.visual = gaussian(0.010, 0, 0, 1e-8);  // precise
        cov->step(s);
        kalman->step(s);
    }
    EXPECT_NEAR(cov->pose().mean.x(), 2.0, 0.01);  // follows the precise source
    // Paper 003's fixed blend C = 0.7 towards the wheels lands in between.
    EXPECT_GT(kalman->pose().mean.x(), 2.0);
    EXPECT_LT(kalman->pose().mean.x(), 2.4);
}
