// A run's folder read for the 3D view: nodes with their segments, edges by kind, the cloud
// decimated, errors against the truth; a damaged folder named.
#include <lodestone/graphslam/Se3Pose.h>
#include <lodestone/maps/SavedMap.h>
#include <lodestone/view/SceneBuilder.h>
#include <lodestone/view/SceneContent.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "RunFolder.h"
#include "TestPaths.h"

using namespace lodestone;

namespace {
std::size_t countKind(const view::SceneContent& c, view::EdgeKind kind, const std::string& closer = "") {
    return static_cast<std::size_t>(std::count_if(c.edges.begin(), c.edges.end(), [&](const view::ViewEdge& e) {
        return e.kind == kind && (closer.empty() || e.closer == closer);
    }));
}
}  // namespace

TEST(SceneContent, ARunsFolderGivesNodesBySegmentEdgesByKindAndTheCloud) {
    test::TempDir dir;
    test::writeRunFolder(dir.path().string(), false);
    view::RunReadOptions options;
    options.maxPoints = 100;
    const view::SceneContent c = view::readRunFolder(dir.path().string(), options);
    ASSERT_EQ(c.nodes.size(), 20u);
    EXPECT_EQ(c.segments(), 2);
    EXPECT_EQ(c.node(9)->segment, 0);
    EXPECT_EQ(c.node(10)->segment, 1);
    EXPECT_TRUE(c.node(3)->keyframe);
    EXPECT_FALSE(c.node(4)->keyframe);
    EXPECT_EQ(countKind(c, view::EdgeKind::Odometry), 18u);  // 19 steps but the kidnap's
    EXPECT_EQ(countKind(c, view::EdgeKind::Closure, "OrbSubmapERD"), 1u);
    EXPECT_EQ(countKind(c, view::EdgeKind::Closure, "MagneticWindowERD"), 1u);
    EXPECT_EQ(countKind(c, view::EdgeKind::RefusedClosure), 1u);
    EXPECT_EQ(countKind(c, view::EdgeKind::Closure, view::kRelocationCloser), 1u);
    EXPECT_EQ(c.cloud.size(), 100u);  // 1000 points, every 10th
    EXPECT_FLOAT_EQ(c.cloud.xyz[3], 0.04f);
    EXPECT_EQ(c.cloud.rgb[5], 10);
    EXPECT_TRUE(c.truth.empty());
    EXPECT_TRUE(std::isnan(c.maxError));
}

TEST(SceneContent, EachNodesErrorAgainstTheTruth) {
    test::TempDir dir;
    test::writeRunFolder(dir.path().string(), true);
    const view::SceneContent c = view::readRunFolder(dir.path().string());
    // One node of 20 half a metre off: after the rigid alignment it carries the largest error.
    ASSERT_FALSE(std::isnan(c.maxError));
    EXPECT_EQ(c.nodes.back().error, c.maxError);
    EXPECT_GT(c.maxError, 0.4);
    for (std::size_t i = 0; i + 1 < c.nodes.size(); ++i) EXPECT_LT(c.nodes[i].error, 0.1) << i;
    EXPECT_FALSE(c.truth.empty());
}

TEST(SceneContent, TheDenseModelIsReadAndDrawnInsteadOfTheCloud) {
    test::TempDir dir;
    test::writeRunFolder(dir.path().string(), true);  // (with mesh.ply)
    const view::SceneContent c = view::readRunFolder(dir.path().string());
    ASSERT_EQ(c.mesh.size(), 2u);
    EXPECT_EQ(c.mesh.xyz.size(), 12u);
    EXPECT_EQ(c.mesh.triangles[5], 3);
    EXPECT_EQ(c.mesh.rgb[0], 200);
    const auto names = view::layerNames(*view::buildScene(c));
    EXPECT_NE(std::find(names.begin(), names.end(), "mesh"), names.end());
    EXPECT_EQ(std::find(names.begin(), names.end(), "cloud"), names.end());
    // A face naming a vertex that is not there: named.
    std::string bytes = test::readTextFile(dir.file("mesh.ply"));
    bytes[bytes.size() - 4] = 9;  // the last index: 3 -> 9
    std::ofstream(dir.file("mesh.ply"), std::ios::binary) << bytes;
    try {
        view::readRunFolder(dir.path().string());
        FAIL() << "a face out of range was read";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("mesh.ply: face 1 names vertex 9"), std::string::npos) << e.what();
    }
}

TEST(SceneContent, AMissingOrDamagedFileIsNamed) {
    test::TempDir dir;
    const std::string d = dir.path().string();
    try {
        view::readRunFolder(d);
        FAIL() << "an empty folder was read";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("graph.graph"), std::string::npos) << e.what();
    }
    test::writeRunFolder(d, false);
    // map.ply cut short
    std::filesystem::resize_file(dir.file("map.ply"), std::filesystem::file_size(dir.file("map.ply")) - 100);
    try {
        view::readRunFolder(d);
        FAIL() << "a cut map.ply was read";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("map.ply"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("cut short"), std::string::npos) << e.what();
    }
    view::RunReadOptions noCloud;
    noCloud.maxPoints = 0;
    EXPECT_NO_THROW(view::readRunFolder(d, noCloud));
    // nodes.csv without a row for a node of the graph
    std::ofstream(dir.file("nodes.csv")) << "node,timestamp,segment,keyframe,engine_ms\n0,1,0,1,0\n";
    try {
        view::readRunFolder(d, noCloud);
        FAIL() << "a node without its row was read";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("nodes.csv"), std::string::npos) << e.what();
    }
}

TEST(SceneContent, ASavedMapsEdgesAcrossTheChainAreClosures) {
    maps::SavedMap map;
    for (std::uint64_t i = 0; i < 6; ++i) {
        map.graph.nodes[i] = mrpt::poses::CPose3D(double(i), 0, 0, 0, 0, 0);
        graphslam::NodeRecord r;
        r.segment = i < 3 ? 0 : 1;
        r.keyframe = i % 2 == 0;
        map.nodes.push_back(r);
        if (i > 0) map.graph.insertEdge(i - 1, i, mrpt::poses::CPose3DPDFGaussianInf());
    }
    map.graph.insertEdge(0, 4, mrpt::poses::CPose3DPDFGaussianInf());
    const view::SceneContent c = view::fromSavedMap(map);
    EXPECT_EQ(c.segments(), 2);
    EXPECT_EQ(countKind(c, view::EdgeKind::Odometry), 4u);  // 2 -> 3 joins two segments
    EXPECT_EQ(countKind(c, view::EdgeKind::Closure), 2u);
    EXPECT_TRUE(c.node(4)->keyframe);
}

TEST(SceneBuilder, EachLayerIsANamedObject) {
    test::TempDir dir;
    test::writeRunFolder(dir.path().string(), true);
    const auto scene = view::buildScene(view::readRunFolder(dir.path().string()));
    const auto names = view::layerNames(*scene);
    for (const char* name : {"floor", "mesh", "truth", "odometry", "closures/MagneticWindowERD",
                             "closures/OrbSubmapERD", "refused", "nodes"})
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
    // Without the mesh, the cloud in its place; without the truth, no truth.
    view::Layers some;
    some.mesh = some.truth = false;
    const auto fewer = view::layerNames(*view::buildScene(view::readRunFolder(dir.path().string()), some));
    EXPECT_NE(std::find(fewer.begin(), fewer.end(), "cloud"), fewer.end());
    EXPECT_EQ(std::find(fewer.begin(), fewer.end(), "mesh"), fewer.end());
    EXPECT_EQ(std::find(fewer.begin(), fewer.end(), "truth"), fewer.end());
    EXPECT_EQ(fewer.size() + 1, names.size());
}
