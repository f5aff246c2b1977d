#include <gtest/gtest.h>
#include <lodestone/sim/RgbdRenderer.h>
#include <lodestone/vision/RgbdVisualOdometry.h>
#include <lodestone/vision/depth/PointToPlaneIcp.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <opencv2/imgproc.hpp>

#include "SimTestFrames.h"
#include "SimTestWorlds.h"

using namespace lodestone::vision;
using lodestone::test::cameraPose;
using lodestone::test::opticalInCamera;
using lodestone::test::render;

namespace {
/** The current frame's pose in the reference's optical frame, from their world poses. */
Eigen::Isometry3d opticalMotion(const Eigen::Isometry3d& ref, const Eigen::Isometry3d& cur) {
    return (ref * opticalInCamera()).inverse() * (cur * opticalInCamera());
}

DepthAlignment alignFrames(const lodestone::sim::World& world, const Eigen::Isometry3d& ref,
                           const Eigen::Isometry3d& cur, const Eigen::Isometry3d& initial) {
    DepthModel model(1);
    model.addReference(sampleDepthCloud(render(world, ref, 11), DepthSampling{}),
                       Eigen::Isometry3d::Identity());
    return PointToPlaneIcp().align(model, sampleDepthCloud(render(world, cur, 12), DepthSampling{}),
                                   initial);
}

/** A plain corridor 2 m wide and 62 m long (x from -2 to 60), nothing at its ends in range (or
 * its walls of another surface). */
lodestone::sim::Scenario plainCorridor(const std::string& surface = "plain") {
    lodestone::sim::Scenario sc = lodestone::test::boxScenario("plain");
    sc.walls.clear();
    for (const double y : {-1.0, 1.0}) {
        lodestone::sim::WallSpec w;
        w.name = "side";
        w.surface = lodestone::sim::SurfaceSpec::parse(surface);
        w.points = {{-2, y}, {60, y}};
        sc.walls.push_back(w);
    }
    return sc;
}

/** A cloud of one point 2 m straight ahead, facing the camera. */
DepthCloud onePointAhead() {
    DepthCloud one;
    one.points = Eigen::Matrix3Xf::Zero(3, 1);
    one.points.col(0) << 0, 0, 2;
    one.normals = Eigen::Matrix3Xf::Zero(3, 1);
    one.normals.col(0) << 0, 0, -1;
    one.sigma = Eigen::VectorXf::Constant(1, 0.01f);
    one.normalVariance = Eigen::VectorXf::Constant(1, 1e-4f);
    return one;
}

double angleOf(const Eigen::Isometry3d& T) { return Eigen::AngleAxisd(T.rotation()).angle(); }

/** The standard deviation the covariance gives along a unit translation direction (optical frame). */
double translationSigma(const DepthAlignment& a, const Eigen::Vector3d& direction) {
    return std::sqrt(direction.dot(a.covariance.bottomRightCorner<3, 3>() * direction));
}
}  // namespace

TEST(DepthCloud, APlaneGivesItsNormalFacingTheCamera) {
    RgbdFrame f;
    f.intrinsics = {100, 100, 79.5, 59.5, 160, 120};
    f.depth = cv::Mat(120, 160, CV_32FC1);
    // The plane z = 2 + 0.5 x, seen from the origin: depth along each pixel's ray.
    for (int v = 0; v < 120; ++v) {
        for (int u = 0; u < 160; ++u) {
            const double xr = (u - 79.5) / 100;
            f.depth.at<float>(v, u) = static_cast<float>(2 / (1 - 0.5 * xr));
        }
    }
    f.depth.at<float>(60, 80) = 0;  // a hole: its neighbours lose their normal
    const DepthCloud c = sampleDepthCloud(f, DepthSampling{40, 0.002, 1.425e-3, 5.0, 0.05});
    ASSERT_GT(c.size(), 800u);
    const Eigen::Vector3f expected = Eigen::Vector3f(0.5f, 0, -1).normalized();
    for (std::size_t i = 0; i < c.size(); ++i) {
        const auto k = static_cast<Eigen::Index>(i);
        EXPECT_NEAR(c.normals.col(k).dot(expected), 1.0f, 1e-4f) << i;
        EXPECT_NEAR(c.points(2, k), 2 + 0.5f * c.points(0, k), 1e-4f);
        EXPECT_NE(c.points(0, k), 0.0f) << "the hole's point is left out";
    }
}

TEST(DepthCloud, NoDepthGivesNoPoints) {
    RgbdFrame f;
    f.depth = cv::Mat(480, 640, CV_32FC1, cv::Scalar(0));
    EXPECT_EQ(sampleDepthCloud(f, DepthSampling{}).size(), 0u);
    f.depth.setTo(std::numeric_limits<float>::quiet_NaN());
    EXPECT_EQ(sampleDepthCloud(f, DepthSampling{}).size(), 0u);
}

// A room's corner (two walls and the floor, all plain: no texture at all) pins every direction:
// a known 6-DoF motion comes back to 1 mm / 0.1 deg from an initial guess of no motion.
TEST(PointToPlaneIcp, RecoversAKnownMotionInARoomsCorner) {
    const auto sc = lodestone::test::boxScenario("plain");
    const lodestone::sim::World world(sc, 3);
    const Eigen::Isometry3d ref = cameraPose({6.6, 1.6, 1.2}, 0.75, 0.4);
    const Eigen::Isometry3d cur = cameraPose({6.66, 1.57, 1.215}, 0.79, 0.38, 0.02);
    const Eigen::Isometry3d truth = opticalMotion(ref, cur);
    const DepthAlignment a = alignFrames(world, ref, cur, Eigen::Isometry3d::Identity());
    ASSERT_TRUE(a.success) << toString(a.failure) << ", " << a.correspondences << " pairs";
    EXPECT_EQ(a.observed, 6);
    const Eigen::Isometry3d err = truth.inverse() * a.T_ref_cur;
    EXPECT_LT(err.translation().norm(), 0.001) << err.translation().transpose();
    EXPECT_LT(angleOf(err), 0.1 * M_PI / 180);
    // The covariance is honest about it: every direction known to well under a centimetre.
    for (int k = 0; k < 6; ++k) EXPECT_LT(std::sqrt(a.covariance(k, k)), 0.005) << k;
}

// Looking along a plain corridor (walls, floor, ceiling, no end within range): the depth pins the
// rotation and the move across, and says the move along was not measured - it keeps the
// initial guess there with a loose covariance, never a confident wrong translation.
TEST(PointToPlaneIcp, InAPlainCorridorTheMoveAlongIsLeftUnobserved) {
    const lodestone::sim::World world(plainCorridor(), 3);
    const Eigen::Isometry3d ref = cameraPose({5.0, 0.1, 1.2}, 0.0, 0.1);
    const Eigen::Isometry3d cur = cameraPose({5.3, 0.13, 1.21}, 0.03, 0.11);
    const Eigen::Isometry3d truth = opticalMotion(ref, cur);
    // The initial guess: 10 cm short along, 2 cm off across, 1 deg off in yaw.
    Eigen::Isometry3d initial = truth;
    initial.translation() += Eigen::Vector3d(0.02, 0, -0.10);
    initial.linear() = initial.linear() * Eigen::AngleAxisd(0.017, Eigen::Vector3d::UnitY());
    const DepthAlignment a = alignFrames(world, ref, cur, initial);
    ASSERT_TRUE(a.success) << toString(a.failure);
    EXPECT_EQ(a.observed, 5);
    // Along the corridor is the reference's optical z (it looks almost straight down it).
    const Eigen::Vector3d along = opticalMotion(ref, cameraPose({6, 0.1, 1.2}, 0, 0.1))
                                      .translation()
                                      .normalized();
    const Eigen::Vector3d err = a.T_ref_cur.translation() - truth.translation();
    EXPECT_GT(translationSigma(a, along), 0.5) << "the move along was not measured";
    EXPECT_NEAR(a.T_ref_cur.translation().dot(along), initial.translation().dot(along), 0.01)
        << "it stays the initial guess's";
    const Eigen::Vector3d across = along.cross(Eigen::Vector3d::UnitY()).normalized();
    EXPECT_LT(std::abs(err.dot(across)), 0.003) << "the move across is measured";
    EXPECT_LT(translationSigma(a, across), 0.005);
    EXPECT_LT(angleOf(truth.inverse() * a.T_ref_cur), 0.2 * M_PI / 180);
}

// A plain wall filling the view fixes the distance and two tilts, not the rest: no motion.
TEST(PointToPlaneIcp, APlainWallAloneGivesNoMotion) {
    const auto sc = lodestone::test::boxScenario("plain");
    const lodestone::sim::World world(sc, 3);
    const Eigen::Isometry3d ref = cameraPose({7.0, 0.0, 1.35}, 0.0);
    const Eigen::Isometry3d cur = cameraPose({7.02, 0.05, 1.35}, 0.02);
    const DepthAlignment a = alignFrames(world, ref, cur, Eigen::Isometry3d::Identity());
    EXPECT_FALSE(a.success);
    EXPECT_EQ(a.failure, DepthAlignFailure::Unobservable);
    EXPECT_EQ(a.observed, 3);
}

// Two plain walls meeting in a corner, 1 m away, no floor or ceiling in view: the depth pins
// all but the rise. A hand pitching the camera 2 deg about itself tilts both walls about their
// centre 1.4 m ahead - a motion the depth cannot tell from the pitch about the camera's own
// centre plus a 5 cm rise. Where the depth is silent, the camera keeps its initial motion:
// the pitch comes back, the rise stays the initial guess's (none), not the surfaces'.
TEST(PointToPlaneIcp, WhereTheDepthPinsNoRiseTheCameraKeepsItsOwn) {
    const auto sc = lodestone::test::boxScenario("plain");
    const lodestone::sim::World world(sc, 3);
    const Eigen::Isometry3d ref = cameraPose({7.0, 2.0, 1.25}, M_PI / 4);
    const Eigen::Isometry3d cur = cameraPose({7.0, 2.0, 1.25}, M_PI / 4, 2 * M_PI / 180);
    const Eigen::Isometry3d truth = opticalMotion(ref, cur);
    const DepthAlignment a = alignFrames(world, ref, cur, Eigen::Isometry3d::Identity());
    ASSERT_TRUE(a.success) << toString(a.failure);
    EXPECT_EQ(a.observed, 5);
    // Up is the reference's optical -y (the camera level).
    const Eigen::Vector3d up = -Eigen::Vector3d::UnitY();
    EXPECT_GT(translationSigma(a, up), 0.5) << "the rise was not measured";
    EXPECT_LT(std::abs(a.T_ref_cur.translation().dot(up)), 0.005)
        << "the camera's rise stays the initial guess's: " << a.T_ref_cur.translation().transpose();
    EXPECT_LT(angleOf(truth.inverse() * a.T_ref_cur), 0.2 * M_PI / 180) << "the pitch is measured";
    EXPECT_LT((a.T_ref_cur.translation() - truth.translation()).norm(), 0.005);
}

TEST(PointToPlaneIcp, NoDepthGivesNoMotion) {
    const auto sc = lodestone::test::boxScenario("plain");
    const lodestone::sim::World world(sc, 3);
    DepthModel model(2);
    model.addReference(sampleDepthCloud(render(world, cameraPose({5.5, 1.0, 1.2}, 0.6, 0.15), 1),
                                        DepthSampling{}),
                       Eigen::Isometry3d::Identity());
    const DepthAlignment a = PointToPlaneIcp().align(model, DepthCloud{}, Eigen::Isometry3d::Identity());
    EXPECT_FALSE(a.success);
    EXPECT_EQ(a.failure, DepthAlignFailure::FewPoints);
    // Nor does a frame full of depth against an empty model (VO's first frame after a reset).
    const DepthCloud full =
        sampleDepthCloud(render(world, cameraPose({5.5, 1.0, 1.2}, 0.6, 0.15), 2), DepthSampling{});
    ASSERT_GT(full.size(), 1000u);
    const DepthModel empty;
    EXPECT_EQ(PointToPlaneIcp().align(empty, full, Eigen::Isometry3d::Identity()).failure,
              DepthAlignFailure::FewPoints);
}

// The model keeps the keyframes before the reference, moved into its frame: a frame that turned
// back towards what only an older keyframe saw still finds its surfaces.
TEST(DepthModel, OlderKeyframesAreMovedIntoTheReferenceFrame) {
    const DepthCloud one = onePointAhead();
    DepthModel model(2);
    model.addReference(one, Eigen::Isometry3d::Identity());
    // The next reference is 0.5 m forward of the first: the old point is 1.5 m ahead of it.
    Eigen::Isometry3d T_new_old = Eigen::Isometry3d::Identity();
    T_new_old.translation() << 0, 0, -0.5;
    DepthCloud two = one;
    two.points.col(0) << 1, 0, 2;
    model.addReference(two, T_new_old);
    DepthModel::Nearest nn;
    ASSERT_TRUE(model.nearest({0, 0, 1.5f}, 0.01f, nn));
    EXPECT_NEAR(nn.point.z(), 1.5f, 1e-6f);
    ASSERT_TRUE(model.nearest({1, 0, 2}, 0.01f, nn));
    // A third reference drops the first keyframe.
    model.addReference(two, Eigen::Isometry3d::Identity());
    EXPECT_EQ(model.keyframeCount(), 2);
    EXPECT_FALSE(model.nearest({0, 0, 1.5f}, 0.01f, nn));
}

// A reference reached by a motion that left directions loose cannot place the keyframes before
// it: they are dropped rather than kept at a guessed place.
TEST(DepthModel, ALooseMotionDropsTheOlderKeyframes) {
    const DepthCloud one = onePointAhead();
    DepthModel model(3);
    model.addReference(one, Eigen::Isometry3d::Identity());
    model.addReference(one, Eigen::Isometry3d::Identity());
    EXPECT_EQ(model.keyframeCount(), 2);
    model.addReference(one, Eigen::Isometry3d::Identity(), false);
    EXPECT_EQ(model.keyframeCount(), 1);
}

TEST(RgbdVisualOdometryParams, DepthKeysAreReadAndChecked) {
    mrpt::config::CConfigFileMemory ini(
        "[vo]\ndepth_alignment = true\ndepth_min_observed = 4\ndepth_model_keyframes = 2\n"
        "depth_grid_columns = 40\ndepth_points_from_cell_mean = true\n");
    RgbdVisualOdometry::Params p;
    EXPECT_FALSE(p.depthSampling.pointsFromCellMean) << "single pixels unless asked for";
    p.loadFromConfigFile(ini, "vo");
    EXPECT_TRUE(p.depthAlignment);
    EXPECT_EQ(p.depthIcp.minObserved, 4);
    EXPECT_EQ(p.depthModelKeyframes, 2);
    EXPECT_EQ(p.depthSampling.columns, 40);
    EXPECT_TRUE(p.depthSampling.pointsFromCellMean);
    EXPECT_EQ(p.gyroDepthMinObserved, 0) << "off unless asked for";
    mrpt::config::CConfigFileMemory withGyro("[vo]\ngyro_depth_min_observed = 3\n");
    p.loadFromConfigFile(withGyro, "vo");
    EXPECT_EQ(p.gyroDepthMinObserved, 3);
    for (const char* bad : {"[vo]\ndepth_min_observed = 7\n", "[vo]\ndepth_model_keyframes = 0\n",
                            "[vo]\ngyro_depth_min_observed = 7\n",
                            "[vo]\ndepth_grid_columns = 2\n", "[vo]\ndepth_aligment = true\n"}) {
        mrpt::config::CConfigFileMemory b(bad);
        RgbdVisualOdometry::Params q;
        try {
            q.loadFromConfigFile(b, "vo");
            ADD_FAILURE() << "accepted: " << bad;
        } catch (const std::exception& e) {
            const std::string key = std::string(bad).substr(5, std::string(bad).find(' ') - 5);
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
        }
    }
}

/** A step of 30 cm down the plain corridor, turned 2 deg: its frames' poses, the true motion
 * (optical frame) and the directions along and across the corridor in it. */
struct CorridorStep {
    Eigen::Isometry3d ref = cameraPose({5.0, 0.1, 1.2}, 0.0, 0.1);
    Eigen::Isometry3d cur = cameraPose({5.3, 0.13, 1.21}, 0.03, 0.11);
    Eigen::Isometry3d truth = opticalMotion(ref, cur);
    Eigen::Vector3d along =
        opticalMotion(ref, cameraPose({6, 0.1, 1.2}, 0, 0.1)).translation().normalized();
    Eigen::Vector3d across = along.cross(Eigen::Vector3d::UnitY()).normalized();

    /** The features' motion as measured: the truth moved by `offset`, with these sigmas. */
    MotionPrior measured(const Eigen::Vector3d& offset, double rotationSigma,
                         double translationSigma) const {
        MotionPrior m;
        m.T_ref_cur = truth;
        m.T_ref_cur.translation() += offset;
        m.covariance.setZero();
        m.covariance.diagonal().head<3>().setConstant(rotationSigma * rotationSigma);
        m.covariance.diagonal().tail<3>().setConstant(translationSigma * translationSigma);
        return m;
    }
    DepthModel model(const lodestone::sim::World& world) const {
        DepthModel m(1);
        m.addReference(sampleDepthCloud(render(world, ref, 11), DepthSampling{}),
                       Eigen::Isometry3d::Identity());
        return m;
    }
};

// Features and depth solved as one: in a plain corridor the depth pins the move across and the
// measured motion (the features') supplies the move along, with its own uncertainty there.
TEST(PointToPlaneIcp, WithAMeasuredMotionTheCorridorsMoveAlongComesFromIt) {
    const lodestone::sim::World world(plainCorridor(), 3);
    const CorridorStep step;
    const auto& [ref, cur, truth, along, across] = step;
    // The measurement: 2 cm off along and 3 cm off across, each with a 5 cm sigma.
    const MotionPrior measured = step.measured(0.02 * along + 0.03 * across, 0.01, 0.05);
    const DepthModel model = step.model(world);
    const DepthAlignment a =
        PointToPlaneIcp().align(model, sampleDepthCloud(render(world, cur, 12), DepthSampling{}),
                                measured.T_ref_cur, &measured);
    ASSERT_TRUE(a.success);
    EXPECT_EQ(a.observed, 5);
    const Eigen::Vector3d err = a.T_ref_cur.translation() - truth.translation();
    EXPECT_LT(std::abs(err.dot(across)), 0.003) << "the depth corrected the move across";
    EXPECT_NEAR(err.dot(along), 0.02, 0.005) << "the move along is the measurement's";
    EXPECT_NEAR(translationSigma(a, along), 0.05, 0.01);
    EXPECT_LT(translationSigma(a, across), 0.005);
    EXPECT_FALSE(a.disagreed) << "3 cm off with a 5 cm sigma is no disagreement: "
                              << a.disagreement;
}

// The same measurement claiming 2 mm where it is 3 cm off across: the two disagree (one of the
// covariances lies, the solve cannot tell which), and the joint covariance widens to cover
// where the solve landed - a graph is not handed a confident wrong step.
TEST(PointToPlaneIcp, AMeasurementThatDisagreesWithTheDepthWidensTheJointCovariance) {
    const lodestone::sim::World world(plainCorridor(), 3);
    const CorridorStep step;
    const auto& [ref, cur, truth, along, across] = step;
    MotionPrior measured = step.measured(0.03 * across, 0.001, 0.002);
    const DepthModel model = step.model(world);
    const DepthCloud current = sampleDepthCloud(render(world, cur, 12), DepthSampling{});
    const DepthAlignment a = PointToPlaneIcp().align(model, current, measured.T_ref_cur, &measured);
    ASSERT_TRUE(a.success);
    EXPECT_TRUE(a.disagreed);
    EXPECT_GT(a.disagreement, 16.81) << "beyond chi-square's 99 % for the 5 directions pinned";
    const double err = (a.T_ref_cur.translation() - truth.translation()).dot(across);
    EXPECT_GT(std::abs(err), 0.002) << "the tight measurement pulled the solve off the depth";
    EXPECT_LT(std::abs(err) / translationSigma(a, across), 3.3)
        << "the covariance covers it: error " << err << ", sigma " << translationSigma(a, across);
    // Told the truth with the same claim, the two agree and nothing widens.
    measured.T_ref_cur = truth;
    const DepthAlignment b = PointToPlaneIcp().align(model, current, truth, &measured);
    ASSERT_TRUE(b.success);
    EXPECT_FALSE(b.disagreed) << b.disagreement;
    EXPECT_LT(translationSigma(b, across), 0.003);
}


// A gyro's rotation and the depth solved as one (`gyro_depth_min_observed`): facing one wall the
// depth pins 3 directions - too few alone - and with the rotation measured the motion counts:
// the turn the gyro's, the distance to the wall the depth's, the move along the wall as loose as
// the carrier allows. Off, the same frame is a failure.
TEST(RgbdVisualOdometry, AGyroAndOneWallSolvedAsOneGiveALooseMotion) {
    const lodestone::sim::World world(plainCorridor("posters"), 3);
    // Facing the wall at y = 1 from 1.1 m; then 4 cm closer, 3 cm along it, turned 2 deg.
    const Eigen::Isometry3d ref = cameraPose({5.0, -0.1, 1.2}, M_PI / 2);
    const Eigen::Isometry3d cur = cameraPose({5.03, -0.06, 1.2}, M_PI / 2 + 0.035);
    const Eigen::Isometry3d truth = opticalMotion(ref, cur);
    const RgbdFrame first = render(world, ref, 11);  // its features start VO ...
    RgbdFrame second = render(world, cur, 12);
    second.gray = cv::Mat1b::zeros(first.gray.size());  // ... the second has none
    second.timestamp = first.timestamp + 0.1;
    RotationPrior gyro;
    gyro.R_ref_cur = truth.linear();
    gyro.sigma = 0.002;
    gyro.translationSigma = 0.05;
    const auto run = [&](int gyroDepthMinObserved) {
        RgbdVisualOdometry::Params p;
        p.depthAlignment = true;
        p.gyroDepthMinObserved = gyroDepthMinObserved;
        RgbdVisualOdometry vo(p);
        vo.process(first);
        return vo.process(second, nullptr, &gyro);
    };
    const VoResult off = run(0);
    EXPECT_FALSE(off.success) << "the depth alone pins " << off.depthObserved << " of 6";
    const VoResult on = run(3);
    ASSERT_TRUE(on.success && on.depthAligned) << toString(on.failure);
    EXPECT_EQ(on.depthObserved, 3);
    EXPECT_LT(angleOf(truth.inverse() * on.T_ref_cur), 0.2 * M_PI / 180);
    // The wall's normal is the optical z; along the wall, the optical x.
    const Eigen::Vector3d err = on.T_ref_cur.translation() - truth.translation();
    EXPECT_LT(std::abs(err.z()), 0.005) << "the distance to the wall is measured";
    const Eigen::Matrix3d C = on.covariance.bottomRightCorner<3, 3>();
    EXPECT_LT(std::sqrt(C(2, 2)), 0.005);
    EXPECT_GT(std::sqrt(C(0, 0)), 0.03) << "the move along the wall is not measured";
    EXPECT_LT(std::abs(err.x()), 3 * std::sqrt(C(0, 0))) << "and its sigma holds the error";
}

// `depth_start`: a plain corridor gives too few features to start VO from; its depth alone
// starts it, and the next frame is aligned by depth (the wheels' prediction starting the ICP):
// the turn and the move across measured, the move along left loose. Without the key VO never
// starts there.
TEST(RgbdVisualOdometry, APlainCorridorStartsFromItsDepthWhereAskedTo) {
    const lodestone::sim::World world(plainCorridor(), 3);
    const Eigen::Isometry3d ref = cameraPose({5.0, 0.1, 1.2}, 0.0, 0.1);
    const Eigen::Isometry3d cur = cameraPose({5.1, 0.12, 1.2}, 0.02, 0.1);
    const Eigen::Isometry3d truth = opticalMotion(ref, cur);
    RgbdFrame first = render(world, ref, 11), second = render(world, cur, 12);
    second.timestamp = first.timestamp + 0.1;
    MotionPrior wheels;  // 3 cm off along the corridor and 1 deg off in heading
    wheels.T_ref_cur = truth;
    wheels.T_ref_cur.translation().z() += 0.03;
    wheels.T_ref_cur.linear() = truth.linear() * Eigen::AngleAxisd(0.017, Eigen::Vector3d::UnitY());
    wheels.covariance.setZero();
    wheels.covariance.diagonal() << 4e-4, 4e-4, 4e-4, 1e-3, 1e-3, 1e-3;
    const auto run = [&](bool depthStart) {
        RgbdVisualOdometry::Params p;
        p.depthAlignment = true;
        p.depthStart = depthStart;
        p.depthIcp.minObserved = 4;
        RgbdVisualOdometry vo(p);
        const VoResult start = vo.process(first);
        EXPECT_LT(start.features, static_cast<std::size_t>(p.ransac.minInliers))
            << "the corridor is meant to be too plain for features";
        return vo.process(second, &wheels);
    };
    EXPECT_FALSE(run(false).success);
    const VoResult on = run(true);
    ASSERT_TRUE(on.success && on.depthAligned) << toString(on.failure);
    EXPECT_GE(on.depthObserved, 4);
    EXPECT_LT(angleOf(truth.inverse() * on.T_ref_cur), 0.1 * M_PI / 180)
        << "the heading comes from the walls, not the wheels' 1 deg";
    const Eigen::Vector3d along =
        opticalMotion(ref, cameraPose({6, 0.1, 1.2}, 0, 0.1)).translation().normalized();
    EXPECT_GT(std::sqrt(along.dot(on.covariance.bottomRightCorner<3, 3>() * along)), 0.05)
        << "the move along is not measured by depth";
}

TEST(RgbdVisualOdometryParams, DepthStartIsReadAndOffByDefault) {
    RgbdVisualOdometry::Params p;
    EXPECT_FALSE(p.depthStart);
    mrpt::config::CConfigFileMemory ini("[vo]\ndepth_alignment = true\ndepth_start = true\n");
    p.loadFromConfigFile(ini, "vo");
    EXPECT_TRUE(p.depthStart);
}
