#include <gtest/gtest.h>
#include <lodestone/eval/RelocationEval.h>

#include <cmath>
#include <cstdio>
#include <fstream>

using namespace lodestone;

namespace {
io::TumPose at(double t, double x, double y, double yaw = 0) {
    return {t, mrpt::poses::CPose3D(x, y, 0, yaw, 0, 0)};
}

/** Truth: a straight drive along x at 1 m/s (t = 0..9), lifted at 5 s, put down at 6 s.
 * The estimate is the truth seen from a frame turned 90 degrees and shifted. */
struct KidnapRun {
    std::vector<io::TumPose> truth, estimate;
    std::vector<io::KidnapEventRecord> events{{1, 5.0, 6.0, 6.0, 0, 0}};
    KidnapRun() {
        for (int i = 0; i < 10; ++i) {
            truth.push_back(at(i, i, 0));
            estimate.push_back(at(i, 2, 1 + i, M_PI / 2));  // x_est = 2 - y, y_est = 1 + x
        }
    }
    eval::ReportedKidnap relocatedAt(int node, double offset) const {
        eval::ReportedKidnap k;
        k.segment = 1;
        k.firstNode = 6;
        k.liftTime = 5.0;
        k.putDownTime = 6.0;
        k.relocated = true;
        k.relocationTime = node;
        k.travel = node - 6;
        k.x = 2;
        k.y = 1 + node + offset;
        k.yaw = M_PI / 2;
        k.deciders = "OrbSubmapERD";
        return k;
    }
};
}  // namespace

TEST(RelocationEval, ARightRelocationIsRightAndAWrongOneIsWrong) {
    KidnapRun r;
    const auto right = eval::evaluateRelocations({r.relocatedAt(8, 0.05)}, r.estimate, {}, r.truth, r.events);
    ASSERT_EQ(right.kidnaps.size(), 1u);
    const auto& v = right.kidnaps[0];
    EXPECT_TRUE(v.detected);
    EXPECT_TRUE(v.relocated);
    EXPECT_NEAR(v.secondsToRelocation, 2.0, 1e-9);
    EXPECT_NEAR(v.positionError, 0.05, 1e-6);
    EXPECT_NEAR(v.yawError, 0, 1e-6);
    EXPECT_FALSE(v.wrong);
    EXPECT_EQ(right.falseDetections, 0u);

    const auto wrong = eval::evaluateRelocations({r.relocatedAt(8, 0.8)}, r.estimate, {}, r.truth, r.events);
    EXPECT_TRUE(wrong.kidnaps[0].wrong);
    const std::string table = eval::formatRelocationEvaluation(wrong);
    EXPECT_NE(table.find("relocated 1 of 1, wrong 1"), std::string::npos) << table;
}

TEST(RelocationEval, ASegmentNoKidnapExplainsIsAFalseDetection) {
    KidnapRun r;
    auto extra = r.relocatedAt(3, 0);
    extra.liftTime = 2.0;
    const auto e = eval::evaluateRelocations({extra, r.relocatedAt(8, 0)}, r.estimate, {}, r.truth, r.events);
    EXPECT_EQ(e.falseDetections, 1u);
    EXPECT_TRUE(e.kidnaps[0].relocated);
}

TEST(RelocationEval, MapDamageComparesTheMapAtTheLiftWithTheEnd) {
    KidnapRun r;
    std::vector<io::TumPose> before(r.estimate.begin(), r.estimate.begin() + 5);
    auto bent = r.estimate;
    bent[4] = at(4, 2.3, 5);  // the last map node pulled 0.3 m by the end of the run
    const auto e = eval::evaluateRelocations({}, bent, before, r.truth, r.events);
    ASSERT_TRUE(e.mapAteBefore && e.mapAteAfter);
    EXPECT_NEAR(*e.mapAteBefore, 0, 1e-9);
    EXPECT_GT(*e.mapAteAfter, 0.05);
    EXPECT_FALSE(e.kidnaps[0].detected);
}

TEST(RelocationEval, ReadsTheReportAndNamesABadOne) {
    const std::string path = testing::TempDir() + "/reloc_report.json";
    std::ofstream(path) << R"({"engine": {"relocalization": {"kidnaps": [
        {"segment": 1, "first_node": 6, "lift_time": 5.0, "put_down_time": null, "relocated": true,
         "relocation_time": 8.0, "travel_to_relocation_m": 2.0, "x": 2, "y": 9, "yaw": 1.5,
         "deciders": "MagneticGpERD+OrbSubmapERD"}]}}})";
    const auto k = eval::readReportedKidnaps(path);
    ASSERT_EQ(k.size(), 1u);
    EXPECT_EQ(k[0].firstNode, 6);
    EXPECT_TRUE(std::isnan(k[0].putDownTime));
    EXPECT_EQ(k[0].deciders, "MagneticGpERD+OrbSubmapERD");
    std::ofstream(path) << R"({"tool": "lodestone-slam"})";
    try {
        eval::readReportedKidnaps(path);
        FAIL();
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("engine.relocalization.kidnaps"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
    }
    std::remove(path.c_str());
}

TEST(RelocationEval, ASegmentMergedOnlyAfterItEndedIsNotRelocated) {
    KidnapRun r;
    auto late = r.relocatedAt(9, 0);
    late.relocated = false;
    late.mergedLate = true;
    late.mergeTime = 40.0;
    const auto e = eval::evaluateRelocations({late}, r.estimate, {}, r.truth, r.events);
    EXPECT_TRUE(e.kidnaps[0].detected);
    EXPECT_FALSE(e.kidnaps[0].relocated);
    EXPECT_FALSE(e.kidnaps[0].wrong);
    EXPECT_NEAR(e.kidnaps[0].secondsToMerge, 34.0, 1e-9);
    const std::string table = eval::formatRelocationEvaluation(e);
    EXPECT_NE(table.find("relocated 0 of 1"), std::string::npos) << table;
    EXPECT_NE(table.find("merged 34 s after put-down by a later pass"), std::string::npos) << table;
}
