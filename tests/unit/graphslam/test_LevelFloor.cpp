// LevelFloor: which level surface is the floor, and which surfaces are taken as level at all,
// decided against the floor seen last; fuseUps: two measured ups of a node.
#include <gtest/gtest.h>
#include <lodestone/graphslam/nrd/LevelFloor.h>

#include <cmath>
#include <map>
#include <random>

using namespace lodestone::graphslam;

namespace {
constexpr double kDeg = M_PI / 180;

/** The optical frame (x right, y down, z forward) on a robot whose x is forward, z up. */
Eigen::Isometry3d opticalOnRobot(double cameraHeight) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
    T.translation() = Eigen::Vector3d(0, 0, cameraHeight);
    return T;
}

/** Level patches in the optical frame of a camera whose up there is `up`: each (height below
 * the camera, nearest and farthest distance ahead) a grid of points with the depth noise of a
 * 1.425e-3 z^2 sensor, normals along the up. */
lodestone::vision::DepthCloud levelCloud(const Eigen::Vector3d& up,
                                         const std::vector<std::array<double, 3>>& patches,
                                         std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, 1);
    // Axes of the level plane: "ahead" the optical z made level, "across" the third.
    const Eigen::Vector3d ahead = (Eigen::Vector3d::UnitZ() - up.z() * up).normalized();
    const Eigen::Vector3d across = up.cross(ahead);
    std::vector<Eigen::Vector3d> pts;
    for (const auto& [below, near, far] : patches) {
        for (double d = near; d <= far; d += 0.1) {
            for (double s = -1.0; s <= 1.0; s += 0.1)
                pts.push_back(-below * up + d * ahead + s * across);
        }
    }
    lodestone::vision::DepthCloud c;
    c.points.resize(3, static_cast<Eigen::Index>(pts.size()));
    c.normals.resize(3, c.points.cols());
    c.sigma.resize(c.points.cols());
    c.normalVariance.resize(c.points.cols());
    for (Eigen::Index k = 0; k < c.points.cols(); ++k) {
        Eigen::Vector3d p = pts[static_cast<std::size_t>(k)];
        const double sigma = 1.425e-3 * p.z() * p.z();
        p *= 1 + sigma * noise(rng) / p.z();  // (along the ray)
        c.points.col(k) = p.cast<float>();
        c.normals.col(k) = (p.dot(up) < 0 ? up : Eigen::Vector3d(-up)).cast<float>();
        c.sigma(k) = static_cast<float>(sigma);
        c.normalVariance(k) = 1e-3f;
    }
    return c;
}

/** Poses of nodes in the map, by ID. */
struct Poses {
    std::map<TNodeID, Eigen::Isometry3d> at;
    std::function<Eigen::Isometry3d(TNodeID)> fn() const {
        return [this](TNodeID n) { return at.at(n); };
    }
};

Eigen::Isometry3d walkedTo(double x, double pitch = 0) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(x, 0, 0);
    T.linear() = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix();
    return T;
}
}  // namespace

TEST(LevelFloor, TheFirstFloorIsTheLowestSurfaceAndLaterOnesFollowIt) {
    LevelFloor floor;
    Poses poses;
    const Eigen::Isometry3d A = opticalOnRobot(1.0);  // (the camera 1 m up the robot)
    const Eigen::Vector3d up(0, -1, 0);               // (level: the optical frame's -y)
    // Node 0: the floor 1.35 m below the camera and a table top 0.6 m below it.
    poses.at[0] = walkedTo(0);
    const auto first =
        floor.observe(0, levelCloud(up, {{1.35, 3.0, 4.5}, {0.6, 1.2, 2.0}}, 1), A, poses.fn());
    ASSERT_TRUE(first);
    EXPECT_LT(std::acos(first->up.z()), 0.2 * kDeg);
    EXPECT_NEAR(first->height, 0.35, 0.01) << "the robot's origin: 1.35 less the camera's 1 m";
    EXPECT_GT(first->heightSigma, 0);
    // Node 1, 2 m on: only the table in view - an up, and no height (the table is 0.75 m off
    // where the floor should be).
    poses.at[1] = walkedTo(2);
    const auto table = floor.observe(1, levelCloud(up, {{0.6, 1.2, 2.0}}, 2), A, poses.fn());
    ASSERT_TRUE(table);
    EXPECT_EQ(table->heightSigma, 0);
    // Node 2: the floor again, and the table; the floor is the one near where it was.
    poses.at[2] = walkedTo(4);
    const auto again =
        floor.observe(2, levelCloud(up, {{0.6, 1.2, 2.0}, {1.37, 3.0, 4.5}}, 3), A, poses.fn());
    ASSERT_TRUE(again);
    EXPECT_NEAR(again->height, 0.37, 0.01);
    EXPECT_EQ(floor.ups(), 3u);
    EXPECT_EQ(floor.heights(), 2u);
    EXPECT_EQ(floor.rejected(), 0u);
}

TEST(LevelFloor, ASurfaceBeyondTheUpGateIsNotTakenForLevel) {
    LevelFloor floor;
    Poses poses;
    const Eigen::Isometry3d A = opticalOnRobot(0.5);
    poses.at[0] = walkedTo(0);
    ASSERT_TRUE(floor.observe(0, levelCloud({0, -1, 0}, {{0.5, 1.0, 2.0}}, 1), A, poses.fn()));
    // Node 1 level in the graph, its view's "floor" a 15 deg ramp: refused, not measured.
    poses.at[1] = walkedTo(1);
    const Eigen::Vector3d ramp(0, -std::cos(15 * kDeg), -std::sin(15 * kDeg));
    EXPECT_FALSE(floor.observe(1, levelCloud(ramp, {{0.5, 1.0, 2.0}}, 2), A, poses.fn()));
    EXPECT_EQ(floor.rejected(), 1u);
    // Node 2 tilted 5 deg in the graph by VO's drift, the floor level: taken, and its up is
    // the floor's in the node's frame - 5 deg off the robot's z, which the graph then corrects.
    poses.at[2] = walkedTo(2, 5 * kDeg);
    const auto tilted =
        floor.observe(2, levelCloud({0, -1, 0}, {{0.5, 1.0, 2.0}}, 3), A, poses.fn());
    ASSERT_TRUE(tilted);
    EXPECT_LT(std::acos(tilted->up.z()), 0.3 * kDeg) << "the camera's view is level";
}

TEST(LevelFloor, NoLevelSurfaceGivesNothing) {
    LevelFloor floor;
    Poses poses;
    poses.at[0] = walkedTo(0);
    // A wall 1 m ahead: its normals along the optical -z, facing the camera.
    lodestone::vision::DepthCloud wall;
    const int n = 21 * 21;
    wall.points.resize(3, n);
    wall.normals.resize(3, n);
    wall.sigma = Eigen::VectorXf::Constant(n, 0.002f);
    wall.normalVariance = Eigen::VectorXf::Constant(n, 1e-3f);
    for (int k = 0; k < n; ++k) {
        wall.points.col(k) = Eigen::Vector3f(-1.0f + 0.1f * static_cast<float>(k % 21),
                                             -1.0f + 0.1f * static_cast<float>(k / 21), 1.0f);
        wall.normals.col(k) = Eigen::Vector3f(0, 0, -1);
    }
    EXPECT_FALSE(floor.observe(0, wall, opticalOnRobot(1.0), poses.fn()));
    EXPECT_EQ(floor.ups(), 0u);
}

TEST(LevelFloor, TwoUpsFuseByTheirSigmasAndDisagreeingOnesDoNot) {
    const AttitudePrior accel{Eigen::Vector3d(std::sin(1 * kDeg), 0, std::cos(1 * kDeg)), 1 * kDeg};
    AttitudePrior seen{Eigen::Vector3d::UnitZ(), 0.3 * kDeg, 0.01};
    seen.height = 0.8;
    const auto both = fuseUps(accel, seen);
    ASSERT_TRUE(both);
    // (weights 1 : 11.1: the floor's up moves a tenth of the way towards the accelerometer's)
    EXPECT_NEAR(std::asin(both->up.x()), 1 * kDeg / (1 + 1 / 0.09), 0.002 * kDeg);
    EXPECT_NEAR(both->sigma, 1 / std::sqrt(1 / std::pow(1 * kDeg, 2) + 1 / std::pow(0.3 * kDeg, 2)),
                1e-12);
    EXPECT_EQ(both->height, 0.8);
    EXPECT_EQ(both->heightSigma, 0.01);
    // 5 deg apart against 1 and 0.3 deg: a ramp the accelerometer feels; not fused.
    const AttitudePrior ramp{Eigen::Vector3d(std::sin(5 * kDeg), 0, std::cos(5 * kDeg)),
                             0.3 * kDeg};
    EXPECT_FALSE(fuseUps(AttitudePrior{Eigen::Vector3d::UnitZ(), 1 * kDeg}, ramp));
}
