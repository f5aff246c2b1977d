#include <gtest/gtest.h>
#include <lodestone/eval/SegmentEval.h>
#include <lodestone/outputs/NodeTable.h>
#include <lodestone/outputs/RunFiles.h>

#include <fstream>
#include <sstream>

#include "EvalCommand.h"
#include "TestPaths.h"

using namespace lodestone;

namespace {
/** A square walk of 80 poses; its second half (segment 1) left 2 m off and turned, as an
 * unjoined segment is; each half exact on its own but for 1 cm on every third pose. */
void writeRun(const test::TempDir& dir) {
    std::vector<outputs::NodeRow> nodes;
    io::TumTrajectoryWriter gt(dir.file("ground_truth.tum")), est(dir.file("trajectory.tum"));
    for (int i = 0; i < 80; ++i) {
        const double t = 100 + 0.5 * i;
        const double x = i < 40 ? 0.1 * i : 4.0, y = i < 40 ? 0.0 : 0.1 * (i - 40);
        gt.write(t, mrpt::poses::CPose3D(x, y, 0, 0, 0, 0));
        const int segment = i < 40 ? 0 : 1;
        const double noise = i % 3 == 0 ? 0.01 : 0.0;
        mrpt::poses::CPose3D p(x, y + noise, 0, 0, 0, 0);
        if (segment == 1) p = mrpt::poses::CPose3D(2, -1, 0, 0.4, 0, 0) + p;
        est.write(t, p);
        nodes.push_back({i, t, segment, false, 1.0});
    }
    outputs::writeNodeTable(dir.file("nodes.csv"), nodes);
    std::ofstream(dir.file("report.json"))
        << R"({"engine": {"node_decider": {"stats": {"vo_gap_seconds": [0.4, 6.5, 1.1]}}}})";
}

using test::evalCmd;
}  // namespace

TEST(SegmentEval, EachSegmentOnItsOwnSeesPastWhereItWasLeft) {
    test::TempDir dir;
    writeRun(dir);
    const auto e = eval::evaluateSegments(outputs::readNodeTable(dir.file("nodes.csv")),
                                          io::readTumTrajectory(dir.file("trajectory.tum")),
                                          io::readTumTrajectory(dir.file("ground_truth.tum")));
    ASSERT_EQ(e.segments.size(), 2u);
    EXPECT_EQ(e.segments[1].segment, 1);
    EXPECT_EQ(e.pooledPairs, 80u);
    EXPECT_GT(e.whole.rmse, 0.3) << "the misplaced half";
    EXPECT_LT(e.pooledRmse, 0.01) << "each half is right to its centimetre of noise";
    EXPECT_GT(e.pooledRmse, 0.003);
    std::vector<double> gaps;
    ASSERT_TRUE(eval::readVoGaps(dir.file("report.json"), gaps));
    EXPECT_EQ(gaps, (std::vector<double>{0.4, 6.5, 1.1}));
}

TEST(SegmentEval, TheAppReportsGapsBesideBothAtes) {
    test::TempDir dir;
    writeRun(dir);
    std::string out, err;
    ASSERT_EQ(evalCmd({"segments", dir.path().string()}, out, err), 0) << err;
    EXPECT_NE(out.find("VO gaps       3, 8.0 s in all, the longest 6.5 s"), std::string::npos) << out;
    EXPECT_NE(out.find("segments      2, each aligned on its own"), std::string::npos) << out;
    // A report with no VO (a wheel-only decider): no gap line, the rest the same.
    std::ofstream(dir.file("report.json")) << R"({"engine": {"node_decider": {"stats": {}}}})";
    ASSERT_EQ(evalCmd({"segments", dir.path().string()}, out, err), 0) << err;
    EXPECT_EQ(out.find("VO gaps"), std::string::npos) << out;
    // A damaged report is named.
    std::ofstream(dir.file("report.json")) << "{ not json";
    EXPECT_EQ(evalCmd({"segments", dir.path().string()}, out, err), 1);
    EXPECT_NE(err.find("report.json"), std::string::npos) << err;
    // No nodes.csv: named.
    std::remove(dir.file("nodes.csv").c_str());
    EXPECT_EQ(evalCmd({"segments", dir.path().string()}, out, err), 1);
    EXPECT_NE(err.find("nodes.csv"), std::string::npos) << err;
}
