#include <gtest/gtest.h>
#include <lodestone/eval/FieldMapPlot.h>

#include <cmath>

using lodestone::eval::FieldMapBuilder;
using lodestone::eval::TrajectoryInterpolator;
using lodestone::io::TumPose;
using mrpt::poses::CPose3D;

namespace {
// A robot driving along +x at 0.5 m/s, a pose every 0.2 s, for 4 s.
std::vector<TumPose> straightRun() {
    std::vector<TumPose> t;
    for (int i = 0; i <= 20; ++i) t.push_back({100.0 + 0.2 * i, CPose3D(0.1 * i, 0, 0, 0, 0, 0)});
    return t;
}
}  // namespace

TEST(TrajectoryInterpolator, BetweenPosesOnlyAndNotAcrossAGapWithMotion) {
    auto traj = straightRun();
    // A kidnap: 10 s later the robot is 5 m away.
    traj.push_back({114.0, CPose3D(2.0, 5.0, 0, 0, 0, 0)});
    traj.push_back({114.2, CPose3D(2.1, 5.0, 0, 0, 0, 0)});
    const TrajectoryInterpolator at(traj, 2.0);
    ASSERT_TRUE(at.at(100.3));
    EXPECT_NEAR(at.at(100.3)->x(), 0.15, 1e-9);
    EXPECT_NEAR(at.at(100.4)->x(), 0.2, 1e-9);  // on a pose exactly
    EXPECT_FALSE(at.at(99.9));                   // before the first
    EXPECT_FALSE(at.at(110.0));                  // inside the kidnap
    EXPECT_FALSE(at.at(115.0));                  // after the last
    EXPECT_NEAR(at.at(114.1)->x(), 2.05, 1e-9);
}

TEST(TrajectoryInterpolator, AStopLongerThanTheGapIsStillKnown) {
    std::vector<TumPose> traj = {{0.0, CPose3D(1, 2, 0, 0, 0, 0)}, {30.0, CPose3D(1.005, 2, 0, 0, 0, 0)}};
    const TrajectoryInterpolator at(traj, 2.0);
    ASSERT_TRUE(at.at(15.0));
    EXPECT_NEAR(at.at(15.0)->y(), 2.0, 1e-9);
}

TEST(TrajectoryInterpolator, RotationIsInterpolatedTheShortWay) {
    std::vector<TumPose> traj = {{0.0, CPose3D(0, 0, 0, M_PI - 0.1, 0, 0)},
                                 {1.0, CPose3D(0, 0, 0, -M_PI + 0.1, 0, 0)}};
    const TrajectoryInterpolator at(traj, 2.0);
    // Half way from 179.4 deg to -179.4 deg through 180, not through 0.
    EXPECT_NEAR(std::abs(at.at(0.5)->yaw()), M_PI, 1e-9);
}

TEST(FieldMapBuilder, ReadingsLandWhereTheSensorWasAndAverage) {
    FieldMapBuilder map(straightRun(), 0.1);
    // A sensor 0.3 m to the robot's left: at t=100.5 the robot is at x=0.25, the sensor at
    // (0.25, 0.3); two readings there average.
    EXPECT_TRUE(map.add(100.5, {0, 0.3, 0}, 40.0, "MAG"));
    EXPECT_TRUE(map.add(100.5, {0, 0.3, 0}, 44.0, "MAG"));
    EXPECT_FALSE(map.add(90.0, {0, 0, 0}, 50.0, "MAG"));
    EXPECT_FALSE(map.add(100.5, {0, 0, 0}, std::nan(""), "MAG"));
    EXPECT_EQ(map.placed(), 2u);
    EXPECT_EQ(map.unplaced(), 2u);
    ASSERT_EQ(map.grid().cells(), 1u);
    map.grid().forEach([](double x0, double y0, double x1, double y1, double mean, std::size_t n) {
        EXPECT_LE(x0, 0.25);
        EXPECT_GE(x1, 0.25);
        EXPECT_LE(y0, 0.3);
        EXPECT_GE(y1, 0.3);
        EXPECT_DOUBLE_EQ(mean, 42.0);
        EXPECT_EQ(n, 2u);
    });
    const cv::Mat3b image = map.render("test");
    EXPECT_GT(image.rows, 100);
}

TEST(TrajectoryInterpolator, PiecesAreCutAtKidnapsOnly) {
    auto traj = straightRun();
    traj.push_back({114.0, CPose3D(2.0, 5.0, 0, 0, 0, 0)});   // after a kidnap
    traj.push_back({144.0, CPose3D(2.005, 5.0, 0, 0, 0, 0)});  // a long stop, not a kidnap
    const auto pieces = TrajectoryInterpolator(traj, 2.0).pieces();
    ASSERT_EQ(pieces.size(), 2u);
    EXPECT_EQ(pieces[0].size(), 21u);
    EXPECT_EQ(pieces[1].size(), 2u);
}
