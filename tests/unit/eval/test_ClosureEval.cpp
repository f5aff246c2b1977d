#include <gtest/gtest.h>
#include <lodestone/eval/ClosureEval.h>
#include <lodestone/eval/ClosureFunnel.h>

#include <cmath>
#include <cstdio>
#include <fstream>

using namespace lodestone;

namespace {

/** Truth: two laps of a 4 m x 4 m square at 0.1 m per node (one node per second), except that
 * on the second lap the north side runs 1 m outside the first: the second lap's revisits are
 * two passes, before and after that side. The estimate is the truth (closures are judged on
 * the truth alone). */
struct TwoLaps {
    std::vector<io::TumPose> truth;
    TwoLaps() {
        const double side = 4.0, step = 0.1;
        const int perSide = static_cast<int>(std::lround(side / step));
        int t = 0;
        for (int lap = 0; lap < 2; ++lap) {
            for (int s = 0; s < 4; ++s) {
                for (int k = 0; k < perSide; ++k, ++t) {
                    const double a = k * step;
                    double x = 0, y = 0, yaw = s * M_PI / 2;
                    if (s == 0) x = a;
                    if (s == 1) x = side, y = a;
                    if (s == 2) x = side - a, y = side + (lap == 1 ? 1.0 : 0.0);
                    if (s == 3) x = 0, y = side - a;
                    truth.push_back({double(t), mrpt::poses::CPose3D(x, y, 0, yaw, 0, 0)});
                }
            }
        }
    }
    /** A closure from node `from` to `to`, measured as the truth has it, then moved by `error`
     * metres along the x of `from`. */
    eval::ReportedClosure closure(int from, int to, double score, double error = 0,
                                  const char* source = "A") const {
        eval::ReportedClosure c;
        c.fromNode = from;
        c.toNode = to;
        c.fromTime = truth[std::size_t(from)].timestamp;
        c.toTime = truth[std::size_t(to)].timestamp;
        c.source = source;
        c.score = score;
        c.measured = truth[std::size_t(to)].pose - truth[std::size_t(from)].pose;
        c.measured.x_incr(error);
        return c;
    }
};

/** A 10 m corridor walked east, back west, and east again, a node every 0.1 m (node k at
 * time k). */
std::vector<io::TumPose> corridorThereBackAndThere() {
    std::vector<io::TumPose> truth;
    int t = 0;
    for (int leg = 0; leg < 3; ++leg) {
        for (int k = 0; k < 100; ++k, ++t) {
            const bool west = leg == 1;
            const double x = west ? 10.0 - 0.1 * k : 0.1 * k;
            truth.push_back({double(t), mrpt::poses::CPose3D(x, 0, 0, west ? M_PI : 0, 0, 0)});
        }
    }
    return truth;
}

}  // namespace

TEST(ClosureEval, RevisitPassesAndRecallAtFullPrecision) {
    TwoLaps run;
    // Lap 2 starts at node 160: east side 200-239 is the first pass, north 240-279 is 1 m off
    // (no revisit), west 280-319 the second pass (with 160-239 joined to the first).
    std::vector<eval::ReportedClosure> closures = {
        run.closure(10, 170, 50),         // right, pass 1
        run.closure(290 - 160, 290, 20),  // right, pass 2, but scores below the wrong one
        run.closure(50, 210, 30, 2.0),    // wrong by 2 m
        run.closure(65, 225, 40, 0.3),    // right (0.3 m within 0.5)
        run.closure(20, 180, 10, 0.0, "B"),
    };
    eval::ClosureEvalOptions whole;  // each revisit one pass
    whole.pieceLength = 100;
    const auto q = eval::evaluateClosures(closures, run.truth, run.truth, whole);
    ASSERT_EQ(q.size(), 2u);
    const auto& a = q[0];
    EXPECT_EQ(a.source, "A");
    EXPECT_EQ(a.passes, 2u);
    EXPECT_EQ(a.proposals, 4u);
    EXPECT_EQ(a.right, 3u);
    EXPECT_EQ(a.wrong, 1u);
    EXPECT_NEAR(a.maxError, 2.0, 1e-9);
    EXPECT_NEAR(a.threshold, 30, 1e-12);
    EXPECT_EQ(a.passesDetected, 2u);
    EXPECT_EQ(a.passesAt100, 1u);  // pass 2's closure scores 20 < 30
    EXPECT_NEAR(a.recallAt100(), 0.5, 1e-12);
    const auto& b = q[1];
    EXPECT_EQ(b.wrong, 0u);
    EXPECT_TRUE(std::isnan(b.threshold));
    EXPECT_EQ(b.passesAt100, 1u);
    const auto table = eval::formatClosureQuality(q, whole);
    EXPECT_NE(table.find("| A | 4 | 3 | 1 |"), std::string::npos) << table;

    // In 2 m pieces: the 8 m revisit is four passes, the 4 m one two; A's right closures end in
    // pieces 1 (node 170), 4 (225) and 5 (290); only the first two above the wrong score.
    const auto pieces = eval::evaluateClosures(closures, run.truth, run.truth);
    EXPECT_EQ(pieces[0].passes, 6u);
    EXPECT_EQ(pieces[0].passesDetected, 3u);
    EXPECT_EQ(pieces[0].passesAt100, 2u);
}

TEST(ClosureEval, ATurnedMeasurementIsWrongWhereItLands) {
    TwoLaps run;
    auto c = run.closure(10, 170, 50);
    // 0.3 rad of heading error alone leaves the position right: only where `to` lands counts.
    c.measured =
        mrpt::poses::CPose3D(c.measured.x(), c.measured.y(), 0, c.measured.yaw() + 0.3, 0, 0);
    auto q = eval::evaluateClosures({c}, run.truth, run.truth);
    EXPECT_EQ(q[0].right, 1u);
    // A closure to a node 3 m further along is wrong.
    q = eval::evaluateClosures({run.closure(10, 200, 50, 3.0)}, run.truth, run.truth);
    EXPECT_EQ(q[0].wrong, 1u);
}

TEST(ClosureEval, EachClosureIsWeighedByTheCovarianceItClaims) {
    TwoLaps run;
    const auto claiming = [](eval::ReportedClosure c, double sx, double sy) {
        c.translationCovariance = Eigen::Vector3d(sx * sx, sy * sy, 1e-6).asDiagonal();
        return c;
    };
    // Node 50 faces +y (the square's second side): its errors lie along that node's x, and the
    // covariance is read in its frame - loose along x, tight across.
    const auto along = claiming(run.closure(50, 210, 5, 0.3), 0.3, 0.01);
    EXPECT_NEAR(eval::closureErrorChi2(along, run.truth[50].pose, run.truth[210].pose), 1.0, 1e-9);
    const std::vector<eval::ReportedClosure> closures = {
        along,                                             // right, inside: 1
        claiming(run.closure(10, 170, 5, 0.3), 0.05, 0.05),  // right, claims too much: 36
        claiming(run.closure(20, 180, 5, 0.6), 0.2, 0.2),    // wrong, inside its claim: 9
        claiming(run.closure(30, 190, 5, 0.6), 0.1, 0.1),    // wrong, outside: 36
        run.closure(40, 200, 5, 0.1),                        // claims no covariance: not weighed
    };
    const auto q = eval::evaluateClosures(closures, run.truth, run.truth);
    ASSERT_EQ(q.size(), 1u);
    EXPECT_EQ(q[0].wrong, 2u);
    EXPECT_EQ(q[0].covarianceJudged, 4u);
    EXPECT_EQ(q[0].insideOwnRegion, 2u);
    EXPECT_EQ(q[0].wrongInsideOwnRegion, 1u);
    EXPECT_NEAR(q[0].consistency(), 0.5, 1e-12);
    const auto table = eval::formatClosureQuality(q, {});
    EXPECT_NE(table.find("| 0.500 (1 of 2) |"), std::string::npos) << table;
}

TEST(ClosureEval, PassesWalkedBackAreCountedApart) {
    const auto truth = corridorThereBackAndThere();
    const auto closure = [&](int from, int to, double error) {
        eval::ReportedClosure c;
        c.fromNode = from;
        c.toNode = to;
        c.fromTime = truth[std::size_t(from)].timestamp;
        c.toTime = truth[std::size_t(to)].timestamp;
        c.source = "A";
        c.score = 1;
        c.measured = truth[std::size_t(to)].pose - truth[std::size_t(from)].pose;
        c.measured.x_incr(error);
        return c;
    };
    // West leg: x <= 7.5 is 5 m of travel after its place on the east leg: 7.5 m of opposite
    // revisit, pieces 2 + 2 + 2 + 1.5. The third leg repeats the first (same way) as well as
    // the second: Same throughout, 10 m in five pieces.
    const std::vector<eval::ReportedClosure> closures = {
        closure(30, 170, 0.0),  // node 170: x = 3.0 west, the east leg's node 30 (opposite)
        closure(50, 250, 0.0),  // node 250: x = 5.0 east, the first leg's node 50 (same)
        closure(60, 160, 1.0),  // opposite, but 1 m off: wrong (score 1 ties: nothing at 100 %)
    };
    const auto q = eval::evaluateClosures(closures, truth, truth);
    ASSERT_EQ(q.size(), 1u);
    const auto& same = q[0].byDirection[int(eval::PassDirection::Same)];
    const auto& opposite = q[0].byDirection[int(eval::PassDirection::Opposite)];
    EXPECT_EQ(opposite.passes, 4u);
    EXPECT_EQ(same.passes, 5u);
    EXPECT_EQ(q[0].passes, 9u);
    EXPECT_EQ(opposite.detected, 1u);
    EXPECT_EQ(same.detected, 1u);
    EXPECT_EQ(q[0].right, 2u);
    EXPECT_EQ(q[0].wrong, 1u);
    EXPECT_EQ(opposite.at100, 0u);
    // The passes themselves, in node order; the two found named by index.
    const auto passes = eval::revisitPasses(truth, truth);
    ASSERT_EQ(passes.size(), 9u);
    ASSERT_EQ(q[0].detectedPasses.size(), 2u);
    const auto& a = passes[q[0].detectedPasses[0]];
    const auto& b = passes[q[0].detectedPasses[1]];
    EXPECT_TRUE(a.first <= 170 && 170 <= a.last && a.direction == eval::PassDirection::Opposite);
    EXPECT_TRUE(b.first <= 250 && 250 <= b.last && b.direction == eval::PassDirection::Same);
    const auto table = eval::formatClosureQuality(q, {});
    EXPECT_NE(table.find("| 5, 0.000 | 4, 0.000 |"), std::string::npos) << table;
}

TEST(ClosureEval, TheFunnelNamesTheStageThatLostEachMissedPass) {
    // Walked east, back west and east again; matcher "A" finds one pass.
    const auto truth = corridorThereBackAndThere();
    eval::ReportedClosure right;
    right.fromNode = 30;
    right.toNode = 170;
    right.fromTime = 30;
    right.toTime = 170;
    right.source = "A";
    right.measured = truth[170].pose - truth[30].pose;
    const auto qualities = eval::evaluateClosures({right}, truth, truth);
    const auto passes = eval::revisitPasses(truth, truth);
    ASSERT_EQ(qualities[0].detectedPasses.size(), 1u);
    const std::size_t found = qualities[0].detectedPasses[0];
    // The decider's funnel: a query in the first missed pass reached stage 1 ("no_fit") and
    // a later one in it stage 0; one in the found pass (not counted); none elsewhere.
    std::size_t missedWithQuery = found == 0 ? 1 : 0;
    const auto node = [&](std::size_t p, std::size_t k) { return passes[p].first + k; };
    const std::string path = ::testing::TempDir() + "funnel_report.json";
    {
        std::ofstream f(path);
        f << "{\"engine\": {\"edge_decider\": {\"class\": \"CompositeERD\", \"children\": ["
          << "{\"class\": \"B\"}, {\"class\": \"A\", \"truth_funnel\": {"
          << "\"stage_names\": {\"0\": \"flat\", \"1\": \"no_fit\"}, \"truth_inside_gate\": 0.5, "
          << "\"query_node\": [" << node(missedWithQuery, 0) << ", " << node(missedWithQuery, 1)
          << ", " << node(found, 0) << "], \"stage\": [1, 0, 0]}}]}}}";
    }
    const auto funnels = eval::readClosureFunnels(path, passes, qualities);
    ASSERT_EQ(funnels.size(), 1u);
    const auto& f = funnels[0];
    EXPECT_EQ(f.decider, "A");
    EXPECT_EQ(f.passes, passes.size());
    EXPECT_EQ(f.missed, passes.size() - 1);
    const int dir = static_cast<int>(passes[missedWithQuery].direction);
    EXPECT_EQ(f.missedBy[dir].at(1), 1u);  // the furthest stage of its queries
    EXPECT_EQ(f.missedBy[dir].count(0), 0u);
    std::size_t noQuery = 0;
    for (int d = 0; d < 2; ++d) noQuery += f.missedBy[d].count(-1) ? f.missedBy[d].at(-1) : 0;
    EXPECT_EQ(noQuery, passes.size() - 2);
    EXPECT_DOUBLE_EQ(f.truthInsideGate, 0.5);
    const auto table = eval::formatClosureFunnels(funnels);
    EXPECT_NE(table.find("no_fit"), std::string::npos) << table;
    // A damaged report names its file.
    {
        std::ofstream f(path);
        f << "{ not json";
    }
    try {
        eval::readClosureFunnels(path, passes, qualities);
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
}
