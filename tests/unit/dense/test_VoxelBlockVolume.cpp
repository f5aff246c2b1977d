// Our voxel-block volume: a frame taken out at the pose it was fused at and fused again at a
// moved pose gives the field (and the mesh) fusing it there first gives; the mesh's triangles
// face the camera that saw them; memory follows the surface.
#include "../sim/SimTestFrames.h"
#include "../sim/SimTestWorlds.h"
#include "MeshCompare.h"

#include <lodestone/dense/TsdfFusion.h>
#include <lodestone/dense/VoxelBlockVolume.h>
#include <lodestone/sim/World.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace lodestone;

namespace {

const sim::World& room() {
    static const sim::World world(test::boxScenario(), 1);
    return world;
}

struct View {
    vision::RgbdFrame frame;
    cv::Mat bgr;
    Eigen::Isometry3d pose;  ///< the optical frame in the world
};

/** Six views of the box room turning round at one place. */
std::vector<View> views() {
    std::vector<View> out;
    for (int k = 0; k < 6; ++k) {
        const Eigen::Isometry3d camera = test::cameraPose({2, 0.5, 1.2}, k * M_PI / 3, 0.2);
        View v{test::render(room(), camera, 30 + k), {}, camera * test::opticalInCamera()};
        cv::cvtColor(v.frame.gray, v.bgr, cv::COLOR_GRAY2BGR);
        out.push_back(v);
    }
    return out;
}

dense::VoxelBlockVolume::Settings settings() {
    dense::VoxelBlockVolume::Settings s;
    s.voxelSize = 0.02;
    s.truncation = 0.08;
    return s;
}

Eigen::Isometry3d moved(const Eigen::Isometry3d& pose) {
    Eigen::Isometry3d wrong = pose;
    wrong.translate(Eigen::Vector3d(0.06, -0.04, 0.03));
    wrong.rotate(Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY()));
    return wrong;
}

/** The largest difference between two volumes' voxels over both volumes' blocks (a voxel
 * absent from one counts as empty there): distance [scaled units], weight, colour. */
struct Difference {
    int tsdf{0}, weight{0}, colour{0};
};
Difference compare(const dense::VoxelBlockVolume& a, const dense::VoxelBlockVolume& b, const std::vector<View>& vs) {
    // Probe every voxel within the truncation band in front of and behind what each view saw.
    Difference d;
    const dense::VoxelBlockVolume::Voxel none{};
    const double v = a.settings().voxelSize;
    for (const View& view : vs)
        for (int y = 0; y < view.frame.depth.rows; y += 4)
            for (int x = 0; x < view.frame.depth.cols; x += 4) {
                const float z = view.frame.depth.at<float>(y, x);
                if (!(z > 0)) continue;
                const auto& K = view.frame.intrinsics;
                const Eigen::Vector3d ray((x - K.cx) / K.fx, (y - K.cy) / K.fy, 1);
                for (double s = -0.1; s <= 0.1; s += v / 2) {
                    const Eigen::Vector3d p = view.pose * (ray * (z + s));
                    const auto* va = a.voxelAt(p);
                    const auto* vb = b.voxelAt(p);
                    const auto& ra = va ? *va : none;
                    const auto& rb = vb ? *vb : none;
                    if (ra.weight == 0 && rb.weight == 0) continue;
                    d.tsdf = std::max(d.tsdf, std::abs(ra.tsdf - rb.tsdf));
                    d.weight = std::max(d.weight, std::abs(ra.weight - rb.weight));
                    for (int k = 0; k < 3; ++k) d.colour = std::max(d.colour, std::abs(ra.rgb[k] - rb.rgb[k]));
                }
            }
    return d;
}

}  // namespace

TEST(VoxelBlockVolume, AFrameTakenOutAndFusedAtItsMovedPoseGivesTheFieldOfFusingItThere) {
    const auto vs = views();
    dense::VoxelBlockVolume direct(settings()), refused(settings()), doubled(settings());
    for (const View& v : vs) direct.integrate(v.frame.depth, v.bgr, v.frame.intrinsics, v.pose);
    // Frame 2 fused first at a wrong pose (6 cm, 3 degrees off), then corrected.
    for (std::size_t k = 0; k < vs.size(); ++k) {
        const View& v = vs[k];
        const Eigen::Isometry3d at = k == 2 ? moved(v.pose) : v.pose;
        refused.integrate(v.frame.depth, v.bgr, v.frame.intrinsics, at);
        doubled.integrate(v.frame.depth, v.bgr, v.frame.intrinsics, at);
    }
    refused.integrate(vs[2].frame.depth, vs[2].bgr, vs[2].frame.intrinsics, moved(vs[2].pose), -1);
    refused.integrate(vs[2].frame.depth, vs[2].bgr, vs[2].frame.intrinsics, vs[2].pose);
    doubled.integrate(vs[2].frame.depth, vs[2].bgr, vs[2].frame.intrinsics, vs[2].pose);

    const Difference same = compare(direct, refused, vs);
    // Rounding of the integer running average only: 1e-3 of the truncation band, a colour step.
    EXPECT_EQ(same.weight, 0);
    EXPECT_LE(same.tsdf, 33);
    EXPECT_LE(same.colour, 1);
    // Fusing it again without taking it out is not the same field (the test can fail).
    const Difference other = compare(direct, doubled, vs);
    EXPECT_GT(other.weight, 0);
    EXPECT_GT(other.tsdf, 3000);

    const dense::Mesh a = direct.extractMesh(), b = refused.extractMesh();
    ASSERT_GT(a.vertices.size(), 1000u);
    EXPECT_NEAR(double(b.vertices.size()), double(a.vertices.size()), 0.001 * a.vertices.size());
    // Every vertex of one lies on the same grid edge of the other, within rounding.
    EXPECT_GT(test::shareWithin(a.vertices, b.vertices, 1e-3f), 0.99);
}

TEST(VoxelBlockVolume, TakingOutEveryFrameEmptiesTheField) {
    const auto vs = views();
    dense::VoxelBlockVolume volume(settings());
    for (const View& v : vs) volume.integrate(v.frame.depth, v.bgr, v.frame.intrinsics, v.pose);
    ASSERT_FALSE(volume.extractMesh().empty());
    for (const View& v : vs) volume.integrate(v.frame.depth, v.bgr, v.frame.intrinsics, v.pose, -1);
    EXPECT_TRUE(volume.extractMesh().empty());
    EXPECT_EQ(compare(volume, dense::VoxelBlockVolume(settings()), vs).weight, 0);
}

TEST(VoxelBlockVolume, TrianglesFaceTheCameraThatSawThem) {
    // One view of the wall at x = 8 from x = 5: the wall's triangles' normals point back to -x.
    dense::VoxelBlockVolume volume(settings());
    const Eigen::Isometry3d camera = test::cameraPose({5, 0, 1.2}, 0, 0);
    const vision::RgbdFrame f = test::render(room(), camera, 3);
    volume.integrate(f.depth, {}, f.intrinsics, camera * test::opticalInCamera());
    const dense::Mesh mesh = volume.extractMesh();
    std::size_t onWall = 0, facing = 0, backwards = 0;
    for (const auto& t : mesh.triangles) {
        const Eigen::Vector3f a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
        const Eigen::Vector3f n = (b - a).cross(c - a);
        if (std::abs(a.x() - 8) > 0.05 || std::abs(n.x()) < 0.7 * n.norm()) continue;
        ++onWall;
        facing += n.x() < 0;
        backwards += n.x() > 0;
    }

    ASSERT_GT(onWall, 1000u);
    // (a single noisy frame folds the surface here and there: 2 % of the triangles)
    EXPECT_GT(double(facing), 0.97 * double(onWall)) << backwards << " face away";
}

TEST(VoxelBlockVolume, MemoryFollowsTheSurfaceNotTheBoundingBox) {
    // One view of a wall 3 m away: blocks along the wall's truncation band only - far fewer than
    // the view's frustum holds.
    dense::VoxelBlockVolume volume(settings());
    const Eigen::Isometry3d camera = test::cameraPose({5, 0, 1.2}, 0, 0);
    const vision::RgbdFrame f = test::render(room(), camera, 3);
    volume.integrate(f.depth, {}, f.intrinsics, camera * test::opticalInCamera());
    const double blockEdge = 8 * 0.02;
    // The wall seen is about 3.4 m x 2.5 m: ~330 blocks a layer, at most two layers (+ the
    // floor and ceiling strips seen).
    EXPECT_LT(volume.blockCount(), 2000u);
    EXPECT_GT(volume.blockCount(), 300u);
    const double frustumBlocks = 3.0 * 3.4 * 2.5 / 3 / std::pow(blockEdge, 3);
    EXPECT_LT(volume.blockCount(), frustumBlocks / 2);
    EXPECT_EQ(volume.memoryBytes() / volume.blockCount() / 4096, 1u);
}
