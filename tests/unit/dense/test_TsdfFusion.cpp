// The dense model: a simulated room fused from its true poses meshes onto its walls; frames
// with no usable depth change nothing; the mesh file is what was meshed; [dense] is strict.
#include "../sim/SimTestFrames.h"
#include "../sim/SimTestWorlds.h"
#include "TestPaths.h"

#include <lodestone/config/IniSection.h>
#include <lodestone/dense/TsdfFusion.h>
#include <lodestone/sim/World.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

using namespace lodestone;

namespace {

/** The box room's surfaces: walls x = 8, x = -2, y = +-3, floor z = 0, ceiling z = 2.5. */
double distanceToRoom(const Eigen::Vector3f& p) {
    return std::min({std::abs(p.x() - 8), std::abs(p.x() + 2), std::abs(p.y() - 3), std::abs(p.y() + 3),
                     std::abs(p.z()), std::abs(p.z() - 2.5f)});
}

struct Fused {
    dense::Mesh mesh;
    std::size_t frames{0};
};

/** The room seen from four places 1.5 m from its side walls, turning round in eight steps at
 * each, fused from the true poses. */
Fused fuseRoom(const dense::DenseParams& params) {
    static const sim::World world(test::boxScenario(), 1);
    dense::TsdfFusion fusion(params);
    int k = 0;
    for (const Eigen::Vector3d& at : {Eigen::Vector3d(0, -1.5, 1.2), Eigen::Vector3d(0, 1.5, 1.2),
                                     Eigen::Vector3d(4, 1.5, 1.2), Eigen::Vector3d(4, -1.5, 1.2)}) {
        for (int turn = 0; turn < 8; ++turn, ++k) {
            const Eigen::Isometry3d camera = test::cameraPose(at, turn * M_PI / 4, 0.3);
            const vision::RgbdFrame f = test::render(world, camera, 10 + k);
            cv::Mat bgr;
            cv::cvtColor(f.gray, bgr, cv::COLOR_GRAY2BGR);
            fusion.integrate(f.depth, bgr, f.intrinsics, camera * test::opticalInCamera());
        }
    }
    return {fusion.extractMesh(), fusion.framesFused()};
}

}  // namespace

TEST(TsdfFusion, ARoomFusedFromItsTruePosesMeshesOntoItsWalls) {
    // Both volumes: ours and Open3D's.
    for (const auto volume : {dense::DenseParams::Volume::Blocks, dense::DenseParams::Volume::Open3d}) {
        SCOPED_TRACE(volume == dense::DenseParams::Volume::Blocks ? "blocks" : "open3d");
        dense::DenseParams p;
        p.voxelSize = 0.02;
        p.truncation = 0.08;
        p.maxDepth = 3;
        p.volume = volume;
        const Fused f = fuseRoom(p);
        EXPECT_EQ(f.frames, 32u);
        ASSERT_GT(f.mesh.vertices.size(), 10000u);
        ASSERT_GT(f.mesh.triangles.size(), 10000u);
        std::vector<double> d;
        for (const auto& v : f.mesh.vertices) d.push_back(distanceToRoom(v));
        std::sort(d.begin(), d.end());
        const double median = d[d.size() / 2], p95 = d[d.size() * 95 / 100];
        EXPECT_LT(median, p.voxelSize / 2) << "p95 " << p95;
        EXPECT_LT(p95, p.voxelSize) << "median " << median;
        for (const auto& t : f.mesh.triangles)
            for (int k = 0; k < 3; ++k) ASSERT_LT(static_cast<std::size_t>(t[k]), f.mesh.vertices.size());
    }
}

TEST(TsdfFusion, OnlyOurVolumeTakesAFrameOut) {
    dense::DenseParams p;
    const vision::CameraIntrinsics K;
    const cv::Mat depth(K.height, K.width, CV_32F, cv::Scalar(2.0));
    dense::TsdfFusion ours(p);
    ours.integrate(depth, {}, K, Eigen::Isometry3d::Identity());
    EXPECT_EQ(ours.framesFused(), 1u);
    EXPECT_GT(ours.memoryBytes(), 0u);
    ours.deintegrate(depth, {}, K, Eigen::Isometry3d::Identity());
    EXPECT_EQ(ours.framesFused(), 0u);
    EXPECT_TRUE(ours.extractMesh().empty());
    p.volume = dense::DenseParams::Volume::Open3d;
    dense::TsdfFusion theirs(p);
    theirs.integrate(depth, {}, K, Eigen::Isometry3d::Identity());
    EXPECT_THROW(theirs.deintegrate(depth, {}, K, Eigen::Isometry3d::Identity()), std::logic_error);
}

TEST(TsdfFusion, AFrameWithNoUsableDepthChangesNothing) {
    dense::TsdfFusion fusion{dense::DenseParams()};
    const vision::CameraIntrinsics K;
    cv::Mat depth(K.height, K.width, CV_32F, cv::Scalar(0));
    EXPECT_EQ(fusion.integrate(depth, {}, K, Eigen::Isometry3d::Identity()), 0u);
    depth.setTo(std::numeric_limits<float>::quiet_NaN());
    depth.at<float>(0, 0) = -1;
    depth.at<float>(1, 0) = std::numeric_limits<float>::infinity();
    depth.at<float>(2, 0) = 100;  // beyond max_depth
    EXPECT_EQ(fusion.integrate(depth, {}, K, Eigen::Isometry3d::Identity()), 0u);
    EXPECT_EQ(fusion.framesFused(), 0u);
    EXPECT_TRUE(fusion.extractMesh().empty());
    // Wrong types and sizes are refused, not read out of bounds.
    EXPECT_THROW(fusion.integrate(cv::Mat(K.height, K.width, CV_16U), {}, K, Eigen::Isometry3d::Identity()),
                 std::invalid_argument);
    EXPECT_THROW(fusion.integrate(cv::Mat(10, 10, CV_32F, cv::Scalar(1)), {}, K, Eigen::Isometry3d::Identity()),
                 std::invalid_argument);
    EXPECT_THROW(fusion.integrate(depth, cv::Mat(K.height, K.width, CV_8UC1), K, Eigen::Isometry3d::Identity()),
                 std::invalid_argument);
}

TEST(TsdfFusion, GarbageDepthInAFrameDoesNotCorruptTheModel) {
    // The room fused once cleanly and once with a ninth frame of noise and NaN: the surfaces
    // the clean frames made are still where they were.
    dense::DenseParams p;
    p.voxelSize = 0.02;
    p.truncation = 0.08;
    static const sim::World world(test::boxScenario(), 1);
    dense::TsdfFusion fusion(p);
    for (int k = 0; k < 8; ++k) {
        const Eigen::Isometry3d camera = test::cameraPose({2, 0, 1.2}, k * M_PI / 4, 0.2);
        const vision::RgbdFrame f = test::render(world, camera, 10 + k);
        fusion.integrate(f.depth, {}, f.intrinsics, camera * test::opticalInCamera());
    }
    const vision::CameraIntrinsics K = test::render(world, test::cameraPose({2, 0, 1.2}, 0), 1).intrinsics;
    cv::Mat garbage(K.height, K.width, CV_32F);
    cv::randu(garbage, -5, 5);
    for (int y = 0; y < garbage.rows; y += 3) garbage.at<float>(y, y % garbage.cols) = NAN;
    fusion.integrate(garbage, {}, K, test::cameraPose({2, 0, 1.2}, 0) * test::opticalInCamera());
    const dense::Mesh mesh = fusion.extractMesh();
    std::size_t far = 0;
    for (const auto& v : mesh.vertices) far += distanceToRoom(v) > 3 * p.voxelSize;
    // Random depth in [0.3, 5] m at random pixels makes scattered specks; the walls stay.
    EXPECT_LT(double(far) / double(mesh.vertices.size()), 0.05) << far << " of " << mesh.vertices.size();
}

TEST(TsdfFusion, TheMeshFileHoldsTheMesh) {
    test::TempDir dir;
    dense::Mesh m;
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.colours = {{{255, 0, 0}}, {{0, 255, 0}}, {{0, 0, 255}}};
    m.triangles = {{0, 1, 2}};
    dense::writeMeshPly(dir.file("mesh.ply"), m);
    const std::string bytes = test::readTextFile(dir.file("mesh.ply"));
    EXPECT_NE(bytes.find("element vertex 3\n"), std::string::npos);
    EXPECT_NE(bytes.find("element face 1\n"), std::string::npos);
    const std::size_t body = bytes.find("end_header\n") + 11;
    EXPECT_EQ(bytes.size() - body, 3 * (12 + 3) + (1 + 12));
    EXPECT_THROW(dense::writeMeshPly(dir.file("no/such/folder/mesh.ply"), m), std::runtime_error);
    // Read back: the same mesh; cut short or another layout, named.
    const dense::Mesh back = dense::readMeshPly(dir.file("mesh.ply"));
    ASSERT_EQ(back.vertices.size(), 3u);
    EXPECT_EQ(back.vertices[1], m.vertices[1]);
    EXPECT_EQ(back.colours[2], m.colours[2]);
    ASSERT_EQ(back.triangles.size(), 1u);
    EXPECT_EQ(back.triangles[0], m.triangles[0]);
    std::ofstream(dir.file("cut.ply"), std::ios::binary) << bytes.substr(0, bytes.size() - 5);
    EXPECT_THROW(dense::readMeshPly(dir.file("cut.ply")), std::runtime_error);
    std::ofstream(dir.file("cloud.ply")) << "ply\nformat ascii 1.0\nend_header\n";
    EXPECT_THROW(dense::readMeshPly(dir.file("cloud.ply")), std::runtime_error);
}

TEST(DenseParams, KeysAreCheckedWithTheirUnits) {
    const auto read = [](const std::string& text) {
        return dense::DenseParams::read(mrpt::config::CConfigFileMemory(text));
    };
    const auto p = read("[dense]\nvoxel_size = 0.02\ntruncation = 0.06\n");
    EXPECT_EQ(p.voxelSize, 0.02);
    // The noise model's limit: 0.002 + 1.425e-3 z^2 = 0.03 -> z = 4.43 m.
    EXPECT_NEAR(p.fusedDepthLimit(), std::sqrt(0.028 / 1.425e-3), 1e-9);
    EXPECT_EQ(read("").voxelSize, 0.01);
    EXPECT_EQ(read("").volume, dense::DenseParams::Volume::Blocks);
    EXPECT_EQ(read("[dense]\nvolume = open3d\n").volume, dense::DenseParams::Volume::Open3d);
    EXPECT_EQ(read("").fusion, dense::DenseParams::Fusion::AfterRun);
    EXPECT_EQ(read("[dense]\nfusion = while_running\n").fusion, dense::DenseParams::Fusion::WhileRunning);
    for (const char* bad : {"[dense]\nvoxel_sise = 0.01\n", "[dense]\nvoxel_size = 0\n",
                            "[dense]\ntruncation = 0.01\n", "[dense]\nmax_depth = 0.1\n",
                            "[dense]\nnoise_floor = 0.05\n", "[dense]\nevery_keyframe = 0\n",
                            "[dense]\nvolume = openvdb\n", "[dense]\nfusion = sometimes\n",
                            "[dense]\nvolume = open3d\nfusion = while_running\n"})
        EXPECT_THROW(read(bad), config::ConfigError) << bad;
}
