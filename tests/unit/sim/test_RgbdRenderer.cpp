#include <gtest/gtest.h>
#include <lodestone/sim/RgbdRenderer.h>

#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "SimTestWorlds.h"
#include "TestPaths.h"

using namespace lodestone::sim;

class RgbdRendererTest : public ::testing::Test {
  protected:
    void SetUp() override {
        sc_ = lodestone::test::boxScenario();
        world_ = std::make_unique<World>(sc_, 5);
        camera_.width = 640;
        camera_.height = 480;
        camera_.maxRange = 9.0;
    }
    Scenario sc_;
    std::unique_ptr<World> world_;
    CameraSpec camera_;
};

TEST_F(RgbdRendererTest, DepthEqualsTheAnalyticDistanceToAKnownWall) {
    const RgbdRenderer renderer(*world_, camera_, 1);
    const Eigen::Vector3d cam(1.0, 0.5, 1.2);  // the front wall is the plane x = 8
    // Depth along the optical axis of a plane facing the camera is the same for every pixel.
    for (const auto& [r, c] : {std::pair{240, 320}, {200, 250}, {300, 390}, {150, 300}}) {
        EXPECT_NEAR(renderer.idealDepth(cam, 0.0, r, c), 7.0, 1e-9) << r << "," << c;
    }
    // Turned by 10 degrees, the centre ray meets the wall 7 / cos(10) away, at that depth.
    const double yaw = 10 * M_PI / 180;
    const double a = (camera_.cx - 320) / camera_.fx;  // the column's leftward slope
    EXPECT_NEAR(renderer.idealDepth(cam, yaw, 240, 320), 7.0 / (std::cos(yaw) - a * std::sin(yaw)),
                1e-9);
    // A row looking down meets the floor: depth = height / slope.
    const int row = 460;
    const double slope = (row - camera_.cy) / camera_.fy;
    EXPECT_NEAR(renderer.idealDepth(cam, 0.0, row, 320), 1.2 / slope, 1e-9);
}

TEST_F(RgbdRendererTest, NoisyDepthStaysWithinTheSensorModel) {
    const RgbdRenderer renderer(*world_, camera_, 1);
    Random rng(3);
    cv::Mat3b rgb;
    cv::Mat_<uint16_t> depth;
    renderer.render({1.0, 0.5, 1.2}, 0.0, rng, rgb, depth);
    // sigma at 7 m: 1.425e-3 * 49 = 7 cm; disparity steps of 2.85e-3 * 49 = 14 cm.
    double sum = 0;
    int n = 0;
    for (int r = 200; r < 280; ++r) {
        for (int c = 280; c < 360; ++c) {
            ASSERT_GT(depth(r, c), 0);
            EXPECT_NEAR(depth(r, c) / 1000.0, 7.0, 0.4);
            sum += depth(r, c) / 1000.0;
            ++n;
        }
    }
    EXPECT_NEAR(sum / n, 7.0, 0.05);  // unbiased on average
}

TEST_F(RgbdRendererTest, RangeLimitsAndGrazingAnglesGiveNoDepth) {
    camera_.maxRange = 5.0;
    const RgbdRenderer renderer(*world_, camera_, 1);
    Random rng(3);
    cv::Mat3b rgb;
    cv::Mat_<uint16_t> depth;
    renderer.render({1.0, 0.0, 1.2}, 0.0, rng, rgb, depth);
    EXPECT_EQ(depth(240, 320), 0);  // the wall is 7 m away, beyond 5 m
    // Along a side wall (y = 3) from 0.3 m away: column 210 meets it 79 degrees off its normal
    // (no depth), column 100 at 69 degrees (depth).
    renderer.render({0.0, 2.7, 1.2}, 0.0, rng, rgb, depth);
    EXPECT_NEAR(renderer.idealDepth({0.0, 2.7, 1.2}, 0.0, 240, 210),
                0.3 * camera_.fx / (camera_.cx - 210), 1e-9);
    EXPECT_EQ(depth(240, 210), 0);
    EXPECT_NEAR(depth(240, 100) / 1000.0, 0.3 * camera_.fx / (camera_.cx - 100), 0.01);
}

// Posters give a corner detector hundreds of features; plain paint almost none. This is what
// makes the corridor scenarios hard for RGB-D odometry.
TEST(RgbdRendererSurfaces, PostersAreRichPlainWallsArePoor) {
    CameraSpec cam;
    int corners[2];
    const char* surfaces[2] = {"posters", "plain"};
    for (int i = 0; i < 2; ++i) {
        const Scenario sc = lodestone::test::boxScenario(surfaces[i]);
        const World world(sc, 5);
        const RgbdRenderer renderer(world, cam, 1);
        Random rng(3);
        cv::Mat3b rgb;
        cv::Mat_<uint16_t> depth;
        renderer.render({6.5, 0.0, 1.2}, 0.0, rng, rgb, depth);  // 1.5 m from the front wall
        cv::Mat grey;
        cv::cvtColor(rgb(cv::Rect(0, 60, 640, 300)), grey, cv::COLOR_BGR2GRAY);  // wall only
        std::vector<cv::KeyPoint> kp;
        cv::FAST(grey, kp, 20, true);
        corners[i] = static_cast<int>(kp.size());
    }
    EXPECT_GT(corners[0], 150) << "posters";
    EXPECT_LT(corners[1], 10) << "plain";
}

TEST(SurfaceTextureImage, APhotoIsTiledAtItsWidth) {
    lodestone::test::TempDir dir;
    cv::Mat3b photo(40, 80, cv::Vec3b(10, 20, 30));
    photo(cv::Rect(0, 0, 40, 40)).setTo(cv::Vec3b(200, 100, 50));  // left half different
    const auto file = dir.file("photo.png");
    cv::imwrite(file, photo);
    const auto spec = SurfaceSpec::parse("image:" + file + ":0.5");
    EXPECT_EQ(spec.style, SurfaceStyle::Image);
    EXPECT_DOUBLE_EQ(spec.imageWidth, 0.5);
    Random rng(1);
    const auto tex = SurfaceTexture::generate(spec, 2.0, 1.0, 100, rng);
    EXPECT_EQ(tex.raster().cols, 200);
    // Every 0.5 m the photo starts again: its left half, then its right half.
    for (double u : {0.1, 0.6, 1.1, 1.6}) EXPECT_NEAR(tex.sample(u, 0.1)[0], 200, 1) << u;
    for (double u : {0.4, 0.9, 1.4}) EXPECT_NEAR(tex.sample(u, 0.1)[0], 10, 1) << u;
    EXPECT_THROW(SurfaceSpec::parse("image:/nonexistent.png:0"), std::invalid_argument);
    EXPECT_THROW(
        SurfaceTexture::generate(SurfaceSpec::parse("image:/nonexistent.png:1"), 1, 1, 50, rng),
        std::runtime_error);
}

TEST(SurfaceTextureArea, ABoxAveragesTheTexelsItCovers) {
    // A checkerboard of single texels (0 / 200 in the first channel), copied texel for texel.
    lodestone::test::TempDir dir;
    cv::Mat3b photo(40, 80, cv::Vec3b(0, 0, 0));
    for (int r = 0; r < photo.rows; ++r)
        for (int c = 0; c < photo.cols; ++c)
            if ((r + c) % 2) photo(r, c) = cv::Vec3b(200, 50, 50);
    const auto file = dir.file("checker.png");
    cv::imwrite(file, photo);
    Random rng(1);
    auto tex = SurfaceTexture::generate(SurfaceSpec::parse("image:" + file + ":0.8"), 0.8, 0.4,
                                        100, rng);
    EXPECT_THROW(tex.sampleArea(0.2, 0.2, 0.04, 0.04), std::logic_error) << "not prepared";
    tex.prepareAreaSampling();
    ASSERT_EQ(tex.raster().cols, 80);
    // A box of 4 x 4 texels anywhere: half of each.
    for (const auto& [u, v] : {std::pair{0.205, 0.205}, {0.335, 0.115}, {0.615, 0.295}}) {
        EXPECT_NEAR(tex.sampleArea(u, v, 0.04, 0.04)[0], 100, 1e-6) << u << "," << v;
        // A point sample at a texel centre sees that texel only.
        EXPECT_GT(std::abs(tex.sample(u, v)[0] - 100), 10) << u << "," << v;
    }
    // A footprint under one texel is the bilinear sample: magnified, nothing changes.
    for (const auto& [u, v] : {std::pair{0.2031, 0.1012}, {0.5555, 0.3077}}) {
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(tex.sampleArea(u, v, 0.004, 0.002)[c], tex.sample(u, v)[c], 1e-6);
    }
    // A box 8 texels long and one texel high, over the raster's edge: clamped inside.
    EXPECT_NEAR(tex.sampleArea(0.0, 0.2, 0.08, 0.01)[0], 100, 1e-6);
}

TEST_F(RgbdRendererTest, APixelAveragesTheWallOverItsFootprint) {
    // 7 m from the posters a pixel covers 7 / 570 m: 2.5 texels at 200 px/m each way.
    camera_.rgbNoise = 0;
    const Eigen::Vector3d cam(1.0, 0.5, 1.2);
    Scenario areaSc = sc_;
    areaSc.areaFilteredTextures = true;
    const World areaWorld(areaSc, 5);
    cv::Mat3b rgb;
    cv::Mat_<uint16_t> depth;
    Random rng(3);
    RgbdRenderer(areaWorld, camera_, 1).render(cam, 0.0, rng, rgb, depth);
    ASSERT_FALSE(sc_.areaFilteredTextures) << "point sampling is the default";
    cv::Mat3b pointRgb;
    RgbdRenderer(*world_, camera_, 1).render(cam, 0.0, rng, pointRgb, depth);
    const auto& wall = areaWorld.wallTexture(areaWorld.floorPlan().walls()[0].surface);
    const double foot = 7.0 / camera_.fx;
    int differ = 0;
    // (pixels that see the front wall, 0.2 m in from its edges)
    for (int r = 160; r < 310; r += 7) {
        for (int c = 150; c < 560; c += 11) {
            // The front wall runs from (8, -3) to (8, 3): u is y + 3, v the height.
            const double u = cam.y() + 7.0 * (camera_.cx - c) / camera_.fx + 3.0;
            const double v = cam.z() + 7.0 * (camera_.cy - r) / camera_.fy;
            const cv::Vec3f area = wall.sampleArea(u, v, foot, foot), point = wall.sample(u, v);
            for (int ch = 0; ch < 3; ++ch) {
                EXPECT_NEAR(rgb(r, c)[ch], area[ch], 1.0) << r << "," << c;
                EXPECT_NEAR(pointRgb(r, c)[ch], point[ch], 1.0) << r << "," << c;
            }
            differ += std::abs(area[0] - point[0]) > 5;
        }
    }
    EXPECT_GT(differ, 50) << "the footprint's average and the centre's sample differ on posters";
}

TEST_F(RgbdRendererTest, TexturedFractionSaysWhatTheCameraFaces) {
    const RgbdRenderer renderer(*world_, camera_, 1);
    // Facing the posters wall at x = 8 from 4 m: every column ends on it.
    EXPECT_DOUBLE_EQ(renderer.texturedFraction({4.0, 0.0, 1.2}, 0.0), 1.0);
    // Facing the plain wall at x = -2: none does.
    EXPECT_DOUBLE_EQ(renderer.texturedFraction({4.0, 0.0, 1.2}, M_PI), 0.0);
    // Looking at the corner: part of each.
    const double corner = renderer.texturedFraction({6.0, 1.5, 1.2}, M_PI / 4);
    EXPECT_GT(corner, 0.1);
    EXPECT_LT(corner, 0.9);
}

TEST_F(RgbdRendererTest, ATiltedHandHeldCameraSeesWhereItPoints) {
    camera_.depthNoise = 0;  // the analytic depth, exactly
    camera_.disparityStep = 0;
    const RgbdRenderer renderer(*world_, camera_, 1);
    const auto render = [&](double pitch, double roll) {
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.translation() = Eigen::Vector3d(1.0, 0.5, 1.2);
        pose.linear() = (Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                         Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                            .toRotationMatrix();
        Random rng(3);
        cv::Mat3b rgb;
        cv::Mat_<uint16_t> depth;
        renderer.render(pose, rng, rgb, depth);
        return depth;
    };
    const int r = static_cast<int>(camera_.cy), c = static_cast<int>(camera_.cx);
    // The ray through that pixel, with a forward component of 1 (its parameter is the depth).
    const auto ray = [&](double pitch, double roll) {
        return Eigen::Vector3d((Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX())) *
                               Eigen::Vector3d(1, (camera_.cx - c) / camera_.fx, (camera_.cy - r) / camera_.fy));
    };
    // Pitched down 5 deg (MRPT: +pitch turns x towards -z), rolled 6 deg: the ray still meets
    // the wall x = 8, at depth 7 / d_x.
    const double p5 = 5 * M_PI / 180;
    EXPECT_NEAR(render(p5, 0.1)(r, c) / 1000.0, 7.0 / ray(p5, 0.1).x(), 1e-3);
    // Pitched down 20 deg: it meets the floor first, at depth 1.2 / -d_z.
    const double p20 = 20 * M_PI / 180;
    EXPECT_NEAR(render(p20, 0.0)(r, c) / 1000.0, 1.2 / -ray(p20, 0.0).z(), 1e-3);
    EXPECT_NEAR(1.2 / -ray(p20, 0.0).z(), 1.2 / std::sin(p20), 0.01);  // (about the centre ray's)
    // Level, the general path renders what the per-column one does.
    Random rng(3);
    cv::Mat3b rgb;
    cv::Mat_<uint16_t> level;
    renderer.render({1.0, 0.5, 1.2}, 0.0, rng, rgb, level);
    EXPECT_EQ(cv::norm(render(0, 0), level, cv::NORM_INF), 0);
}
