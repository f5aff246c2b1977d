// The live view's snapshot of a run with a kidnap: the kidnapped segment is its own colour
// until the relocation joins it to the map, the map's after.
#include "../graphslam/ScriptedDeciders.h"

#include <SyntheticGraph.h>
#include <lodestone/graphslam/SlamEngine.h>
#include <lodestone/view/EngineSnapshot.h>
#include <lodestone/view/Palette.h>
#include <lodestone/view/SceneBuilder.h>
#include <lodestone/view/Snapshot.h>

#include <gtest/gtest.h>

#include <optional>

using namespace lodestone;

namespace {

/** Two laps of the synthetic loop, the robot kidnapped a third into lap 2; closures from
 * the kidnapped segment back to lap 1. */
std::unique_ptr<graphslam::SlamEngine> kidnappedRun() {
    graphslam::SyntheticGraph::Params p;
    p.laps = 2;
    const auto s = graphslam::SyntheticGraph::make(p);
    std::vector<test::ScriptedNRD::Step> steps;
    for (std::size_t i = 0; i + 1 < s.truth.size(); ++i) steps.push_back({s.graph.edges.find({i, i + 1})->second, 0});
    const std::size_t k = s.nodesPerLap + s.nodesPerLap / 3;
    steps[k - 1].edge.mean = mrpt::poses::CPose3D();
    steps[k - 1].edge.cov_inv = graphslam::planarInformation(100, 100);
    for (std::size_t i = k - 1; i < steps.size(); ++i) steps[i].segment = 1;
    std::vector<graphslam::LoopClosure> closures;
    for (const auto& lc : s.closures)
        if (lc.to >= k) closures.push_back(lc);
    auto erd = std::make_unique<graphslam::CompositeERD>();
    erd->addChild(std::make_unique<test::ScriptedLoopCloser>(std::move(closures)));
    return std::make_unique<graphslam::SlamEngine>(std::make_unique<test::ScriptedNRD>(std::move(steps)),
                                                   std::move(erd), std::make_unique<graphslam::CeresGSO>());
}

}  // namespace

TEST(EngineSnapshot, AKidnappedSegmentIsItsOwnColourUntilItJoinsTheMap) {
    auto engine = kidnappedRun();
    std::optional<view::SceneContent> beforeMerge;
    const auto tick = mrpt::obs::CObservationComment::Create();
    while (engine->process(tick)) {
        const view::SceneContent now = view::snapshotOf(*engine);
        if (engine->stats().relocations == 0 && now.segments() == 2) beforeMerge = now;
    }
    engine->finish();
    ASSERT_TRUE(beforeMerge) << "no snapshot with the kidnapped segment apart";
    const view::SceneContent after = view::snapshotOf(*engine);
    EXPECT_EQ(engine->stats().relocations, 1u);
    EXPECT_EQ(after.segments(), 1);  // every node in the map's group now
    EXPECT_TRUE(after.hasCurrent);
    EXPECT_GT(after.edges.size(), after.nodes.size());  // odometry and the closures
    // The closures that joined the segment to the map are the relocation's, in its colour.
    std::size_t merges = 0;
    for (const auto& e : after.edges) merges += e.closer == view::kRelocationCloser;
    EXPECT_GT(merges, 0u);
    EXPECT_LT(merges, after.edges.size() - after.nodes.size());

    // And so in the picture: nodes alone, from above.
    view::Layers nodesOnly;
    nodesOnly.odometry = nodesOnly.closures = nodesOnly.refused = nodesOnly.cloud = nodesOnly.truth =
        nodesOnly.floor = nodesOnly.field = nodesOnly.current = false;
    const auto colours = [&](const view::SceneContent& c) {
        view::ViewCamera camera = view::framing(c);
        camera.elevationDeg = 90;
        const mrpt::img::CImage image = view::renderScene(*view::buildScene(c, nodesOnly), camera, 400, 400);
        std::set<std::tuple<int, int, int>> seen;
        for (unsigned y = 0; y < image.getHeight(); ++y)
            for (unsigned x = 0; x < image.getWidth(); ++x) {
                const auto* p = image.ptr<std::uint8_t>(x, y);
                for (int s = 0; s < 3; ++s) {
                    const auto c = view::segmentColour(s);
                    if (p[2] == c.R && p[1] == c.G && p[0] == c.B) seen.insert({c.R, c.G, c.B});
                }
            }
        return seen.size();
    };
    try {
        EXPECT_EQ(colours(*beforeMerge), 2u);
        EXPECT_EQ(colours(after), 1u);
    } catch (const std::runtime_error& e) {
        GTEST_SKIP() << "no off-screen OpenGL here: " << e.what();
    }
}
