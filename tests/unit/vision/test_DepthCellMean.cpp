// A depth cloud's points from their cells' mean inverse depth (DepthSampling::pointsFromCellMean,
// opt-in) against single pixels, on the simulated Kinect's depth with its disparity steps.
#include <gtest/gtest.h>
#include <lodestone/sim/RgbdRenderer.h>
#include <lodestone/vision/depth/DepthCloud.h>

#include <cmath>

#include "SimTestFrames.h"
#include "SimTestWorlds.h"

using namespace lodestone::vision;
using lodestone::test::cameraPose;
using lodestone::test::render;

namespace {
/** RMS of the distance to the plane z = `depth` (optical frame) of the points whose normal
 * faces the camera squarely (the wall ahead, not the floor). */
double rmsOffWall(const DepthCloud& c, double depth, std::size_t& used) {
    double sum2 = 0;
    used = 0;
    for (Eigen::Index i = 0; i < c.points.cols(); ++i) {
        if (c.normals(2, i) > -0.9f) continue;
        const double e = c.points(2, i) - depth;
        sum2 += e * e;
        ++used;
    }
    return used > 0 ? std::sqrt(sum2 / static_cast<double>(used)) : NAN;
}
}  // namespace

// A plain wall 3.5 m ahead, where the Kinect's depth comes in steps of 3.5 cm: single pixels
// scatter by the noise and the steps (about 2 cm), the cells' means lie on the wall to a few
// millimetres.
TEST(DepthCloud, CellMeansLieOnAWallWhereSinglePixelsStep) {
    const auto sc = lodestone::test::boxScenario("plain");
    const lodestone::sim::World world(sc, 3);
    const RgbdFrame f = render(world, cameraPose({4.5, 0.0, 1.25}, 0.0), 5);
    DepthSampling single, means;
    single.pointsFromCellMean = false;
    means.pointsFromCellMean = true;
    std::size_t nSingle = 0, nMeans = 0;
    const double rmsSingle = rmsOffWall(sampleDepthCloud(f, single), 3.5, nSingle);
    const double rmsMeans = rmsOffWall(sampleDepthCloud(f, means), 3.5, nMeans);
    ASSERT_GT(nSingle, 500u);
    EXPECT_EQ(nMeans, nSingle) << "the same points, only their depth differs";
    EXPECT_GT(rmsSingle, 0.010);
    EXPECT_LT(rmsMeans, 0.005);
    EXPECT_LT(rmsMeans, rmsSingle / 3);
}

// A hole in the cell leaves pixel pairs mirrored about the point: the mean of the inverse
// depth (linear across a plane) is still the plane's at the point.
TEST(DepthCloud, ACellMeanAroundAHoleStaysOnThePlane) {
    RgbdFrame f;
    f.intrinsics = {100, 100, 79.5, 59.5, 160, 120};
    f.depth = cv::Mat(120, 160, CV_32FC1);
    for (int v = 0; v < 120; ++v) {
        for (int u = 0; u < 160; ++u) {
            const double xr = (u - 79.5) / 100, yr = (v - 59.5) / 100;
            f.depth.at<float>(v, u) = static_cast<float>(2 / (1 - 0.5 * xr - 0.2 * yr));
        }
    }
    f.depth.at<float>(41, 43) = 0;
    f.depth.at<float>(62, 78) = std::numeric_limits<float>::quiet_NaN();
    DepthSampling s{40, 0.002, 1.425e-3, 5.0, 0.05};
    s.pointsFromCellMean = true;
    const DepthCloud c = sampleDepthCloud(f, s);
    ASSERT_GT(c.size(), 500u);
    for (Eigen::Index k = 0; k < c.points.cols(); ++k) {
        EXPECT_NEAR(c.points(2, k), 2 + 0.5f * c.points(0, k) + 0.2f * c.points(1, k), 2e-4f) << k;
    }
}
