// The model kept while a run goes: keyframes fused at the poses the run had, then re-fused when
// the graph moved them, give the model of fusing them at the final poses; a keyframe without a
// pose yet (a kidnapped segment) is fused once it has one; the farthest moved go first.
#include "../sim/SimTestFrames.h"
#include "../sim/SimTestWorlds.h"
#include "MeshCompare.h"
#include "TestPaths.h"

#include <lodestone/dense/KeyframeFusion.h>
#include <lodestone/sim/World.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace lodestone;

namespace {

struct View {
    vision::RgbdFrame frame;
    cv::Mat bgr;
    Eigen::Isometry3d pose;  ///< the optical frame in the world
};

std::vector<View> views() {
    static const sim::World world(test::boxScenario(), 1);
    std::vector<View> out;
    for (int k = 0; k < 5; ++k) {
        const Eigen::Isometry3d camera = test::cameraPose({1 + 0.4 * k, 0.3, 1.2}, 0.3 * k, 0.1);
        View v{test::render(world, camera, 50 + k), {}, camera * test::opticalInCamera()};
        cv::cvtColor(v.frame.gray, v.bgr, cv::COLOR_GRAY2BGR);
        out.push_back(v);
    }
    return out;
}

dense::DenseParams params() {
    dense::DenseParams p;
    p.voxelSize = 0.02;
    p.truncation = 0.08;
    return p;
}

/** The share of b's vertices with no vertex of a within 1 mm. */
double unmatched(const dense::Mesh& a, const dense::Mesh& b) {
    return 1.0 - test::shareWithin(a.vertices, b.vertices, 1e-3f);
}

Eigen::Isometry3d drifted(const Eigen::Isometry3d& pose, int k) {
    Eigen::Isometry3d wrong = pose;
    wrong.pretranslate(Eigen::Vector3d(0.03 * k, -0.02 * k, 0));
    wrong.rotate(Eigen::AngleAxisd(0.01 * k, Eigen::Vector3d::UnitY()));
    return wrong;
}

}  // namespace

TEST(KeyframeFusion, KeyframesRefusedWhereTheGraphMovedThemGiveTheModelOfTheirFinalPoses) {
    test::TempDir dir;
    const auto vs = views();
    dense::TsdfFusion direct(params());
    for (const View& v : vs) direct.integrate(v.frame.depth, v.bgr, v.frame.intrinsics, v.pose);

    dense::KeyframeFusion running(params(), dir.file("frames.bin"));
    // The run fuses each keyframe where odometry put it (drifting), then the graph corrects.
    for (std::size_t k = 0; k < vs.size(); ++k)
        running.add(k, vs[k].frame.depth, vs[k].bgr, vs[k].frame.intrinsics, drifted(vs[k].pose, int(k)));
    const dense::Mesh before = running.extractMesh();
    EXPECT_GT(unmatched(direct.extractMesh(), before), 0.2);  // drifted: not the same model
    const auto truth = [&](std::uint64_t id) { return std::optional<Eigen::Isometry3d>(vs[id].pose); };
    // Keyframe 0 did not move; the other four did.
    EXPECT_EQ(running.refuseMoved(truth), 4u);
    EXPECT_EQ(running.refuseMoved(truth), 0u);  // nothing left to move
    const dense::Mesh after = running.extractMesh();
    const dense::Mesh expected = direct.extractMesh();
    ASSERT_GT(expected.vertices.size(), 1000u);
    EXPECT_LT(unmatched(expected, after), 0.01);
    EXPECT_LT(unmatched(after, expected), 0.01);
    const auto stats = running.stats();
    EXPECT_EQ(stats.keyframes, 5u);
    EXPECT_EQ(stats.refusions, 4u);
    EXPECT_EQ(stats.failures, 0u);
    EXPECT_EQ(stats.spillBytes, 5u * 640 * 480 * 7);
}

TEST(KeyframeFusion, AKeyframeWithoutAPoseIsFusedOnceItHasOne) {
    test::TempDir dir;
    const auto vs = views();
    dense::KeyframeFusion running(params(), dir.file("frames.bin"));
    running.add(7, vs[1].frame.depth, vs[1].bgr, vs[1].frame.intrinsics, std::nullopt);
    EXPECT_TRUE(running.extractMesh().empty());
    const auto none = [](std::uint64_t) { return std::optional<Eigen::Isometry3d>(); };
    EXPECT_EQ(running.refuseMoved(none), 0u);
    EXPECT_THROW(running.add(7, vs[1].frame.depth, {}, vs[1].frame.intrinsics, vs[1].pose), std::invalid_argument);
    const auto merged = [&](std::uint64_t) { return std::optional<Eigen::Isometry3d>(vs[1].pose); };
    EXPECT_EQ(running.refuseMoved(merged), 1u);
    EXPECT_FALSE(running.extractMesh().empty());
    EXPECT_EQ(running.stats().keyframes, 1u);
}

TEST(KeyframeFusion, TheFarthestMovedAreRefusedFirstWithinABudget) {
    test::TempDir dir;
    const auto vs = views();
    dense::KeyframeFusion running(params(), dir.file("frames.bin"));
    for (std::size_t k = 0; k < 3; ++k)
        running.add(k, vs[k].frame.depth, {}, vs[k].frame.intrinsics, vs[k].pose);
    // Moved by 1.5, 9 and 4 cm: a budget of one takes keyframe 1.
    const double by[] = {0.015, 0.09, 0.04};
    const auto movedPose = [&](std::uint64_t id) {
        Eigen::Isometry3d p = vs[id].pose;
        p.pretranslate(Eigen::Vector3d(by[id], 0, 0));
        return std::optional<Eigen::Isometry3d>(p);
    };
    EXPECT_EQ(running.refuseMoved(movedPose, 1), 1u);
    EXPECT_EQ(running.stats().refusions, 1u);
    // Keyframe 1 is where it moved to now: the rest are left, 2 before 0.
    EXPECT_EQ(running.refuseMoved(movedPose), 2u);
    EXPECT_EQ(running.stats().refusions, 3u);
    // Half a voxel (1 cm) is the tolerance at the farthest fused depth: a move of 5 mm is not refused.
    const auto slightly = [&](std::uint64_t id) {
        Eigen::Isometry3d p = *movedPose(id);
        p.pretranslate(Eigen::Vector3d(0.005, 0, 0));
        return std::optional<Eigen::Isometry3d>(p);
    };
    EXPECT_EQ(running.refuseMoved(slightly), 0u);
}

TEST(KeyframeFusion, AStoreThatCannotBeWrittenIsNamed) {
    try {
        dense::KeyframeFusion running(params(), "/no/such/folder/frames.bin");
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("/no/such/folder/frames.bin"), std::string::npos) << e.what();
    }
    dense::DenseParams open3d = params();
    open3d.volume = dense::DenseParams::Volume::Open3d;
    test::TempDir dir;
    EXPECT_THROW(dense::KeyframeFusion(open3d, dir.file("frames.bin")), std::invalid_argument);
}
