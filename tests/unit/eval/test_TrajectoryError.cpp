#include <gtest/gtest.h>
#include <lodestone/eval/TrajectoryError.h>

#include <cmath>

using namespace lodestone;

namespace {
io::TumPose at(double t, double x, double y, double yaw = 0) {
    return {t, mrpt::poses::CPose3D(x, y, 0, yaw, 0, 0)};
}
}  // namespace

TEST(TrajectoryError, AssociationIsOneToOneWithinTheTolerance) {
    const std::vector<io::TumPose> est = {at(1.000, 0, 0), at(1.005, 0, 0), at(2.0, 0, 0),
                                          at(3.5, 0, 0)};
    const std::vector<io::TumPose> gt = {at(1.003, 0, 0), at(2.015, 0, 0), at(3.0, 0, 0)};
    const auto pairs = eval::associate(est, gt, 0.02);
    ASSERT_EQ(pairs.size(), 2u);
    EXPECT_EQ(pairs[0], (std::pair<std::size_t, std::size_t>{1, 0}));  // 2 ms beats 3 ms
    EXPECT_EQ(pairs[1], (std::pair<std::size_t, std::size_t>{2, 1}));
}

TEST(TrajectoryError, AteIgnoresARigidOffsetAndMeasuresTheRest) {
    std::vector<io::TumPose> gt, moved, scaled;
    for (int i = 0; i < 4; ++i) {
        gt.push_back(at(i, i, 0));
        // The same path seen from another frame: rotated 30 degrees and shifted.
        const double c = std::cos(0.5), s = std::sin(0.5);
        moved.push_back(at(i + 0.01, 3 + c * i, -2 + s * i, 0.5));
        scaled.push_back(at(i, 1.1 * i, 0));
    }
    const auto rigid = eval::absoluteTrajectoryError(moved, gt);
    EXPECT_EQ(rigid.pairs, 4u);
    EXPECT_NEAR(rigid.rmse, 0.0, 1e-9);
    // 10 % too long: the best rigid fit centres it, residuals 0.1 |x - 1.5| = .15 .05 .05 .15.
    const auto r = eval::absoluteTrajectoryError(scaled, gt);
    EXPECT_NEAR(r.rmse, std::sqrt((2 * 0.15 * 0.15 + 2 * 0.05 * 0.05) / 4), 1e-9);
    EXPECT_NEAR(r.max, 0.15, 1e-9);
    EXPECT_NEAR(r.mean, 0.1, 1e-9);
}

TEST(TrajectoryError, RpePerSecondAndPerMetre) {
    std::vector<io::TumPose> gt, est;
    for (int i = 0; i <= 100; ++i) {
        const double t = 0.1 * i;
        gt.push_back(at(t, 1.0 * t, 0));   // 1 m/s
        est.push_back(at(t, 1.1 * t, 0));  // 10 % too fast
    }
    const auto perSecond = eval::relativePoseError(est, gt, eval::RpeInterval::Seconds, 1.0);
    EXPECT_GT(perSecond.pairs, 80u);
    EXPECT_NEAR(perSecond.translationRmse, 0.1, 1e-9);
    EXPECT_NEAR(perSecond.rotationRmse, 0.0, 1e-12);
    const auto perMetre = eval::relativePoseError(est, gt, eval::RpeInterval::Metres, 1.0);
    EXPECT_NEAR(perMetre.translationRmse, 0.1, 1e-9);
    // A heading error shows up in rotation.
    std::vector<io::TumPose> turned;
    for (int i = 0; i <= 100; ++i) turned.push_back(at(0.1 * i, 0.1 * i, 0, 0.01 * i));
    const auto rot = eval::relativePoseError(turned, gt, eval::RpeInterval::Seconds, 1.0);
    EXPECT_NEAR(rot.rotationRmse, 0.1, 1e-9);
}
