#include <lodestone/outputs/ClosureTable.h>
#include <lodestone/outputs/NodeTable.h>
#include <lodestone/outputs/RunFiles.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

using namespace lodestone;

namespace {
std::string slurp(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}
}  // namespace

TEST(RunFiles, EveryFileHasOneUniqueName) {
    std::set<std::string> names;
    for (const auto& f : outputs::runFiles()) {
        EXPECT_TRUE(names.insert(f.name).second) << f.name;
        EXPECT_EQ(outputs::fileName(f.file), std::string(f.name));
    }
    EXPECT_EQ(outputs::pathIn("out/run", outputs::RunFile::Closures), "out/run/closures.csv");
}

TEST(ClosureTable, WhatIsWrittenReadsBackAndWritesTheSameBytes) {
    const std::string path = ::testing::TempDir() + "closures_round_trip.csv";
    outputs::ClosureRow a;
    a.fromNode = 12;
    a.toNode = 3;
    a.fromTime = 1.25;
    a.toTime = 0.5;
    a.source = "MagneticWindowERD";
    a.matchId = 7;
    a.score = -0.75;
    a.strong = true;
    a.kept = true;
    a.measured = mrpt::poses::CPose3D(0.5, -0.25, 0.0, 0.125, 0.0, 0.0);
    a.translationCovariance << 0.04, 0.01, 0, 0.01, 0.09, 0, 0, 0, 1e-6;
    outputs::ClosureRow b = a;
    b.source = "OrbSubmapERD";
    b.hypothesis = true;
    b.kept = false;
    b.strong = false;
    outputs::writeClosureTable(path, {a, b});
    const auto rows = outputs::readClosureTable(path);
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0].fromNode, 12);
    EXPECT_EQ(rows[0].source, "MagneticWindowERD");
    EXPECT_EQ(rows[0].matchId, 7u);
    EXPECT_TRUE(rows[0].strong);
    EXPECT_FALSE(rows[0].hypothesis);
    EXPECT_TRUE(rows[1].hypothesis);
    EXPECT_FALSE(rows[1].kept);
    EXPECT_NEAR(rows[0].measured.yaw(), 0.125, 1e-8);
    EXPECT_NEAR(rows[0].measured.y(), -0.25, 1e-6);
    EXPECT_TRUE(rows[0].translationCovariance.isApprox(a.translationCovariance, 1e-9))
        << rows[0].translationCovariance;
    const std::string again = ::testing::TempDir() + "closures_round_trip_again.csv";
    outputs::writeClosureTable(again, rows);
    EXPECT_EQ(slurp(path), slurp(again));
}

TEST(ClosureTable, AMalformedLogNamesFileAndLine) {
    const std::string path = ::testing::TempDir() + "closures_bad.csv";
    {
        std::ofstream f(path);
        f << "from_node,to_node,from_time,to_time,source,match_id,score,strong,hypothesis,kept,"
             "x,y,z,yaw,pitch,roll\n"
          << "1,2,0.5,1.5,A,0,3,0,0,1,0.1,0,0,0,0,0\n"
          << "1,2,0.5,nan,A,0,3,0,0,1,0.1,0,0,0,0,0\n";
    }
    try {
        outputs::readClosureTable(path);
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(path + ": line 3"), std::string::npos) << e.what();
    }
    {
        std::ofstream f(path);
        f << "something else\n";
    }
    EXPECT_THROW(outputs::readClosureTable(path), std::runtime_error);
}

TEST(ClosureTable, ALogWrittenBeforeTheCovarianceColumnsStillReads) {
    const std::string path = ::testing::TempDir() + "closures_without_covariance.csv";
    {
        std::ofstream f(path);
        f << "from_node,to_node,from_time,to_time,source,match_id,score,strong,hypothesis,kept,"
             "x,y,z,yaw,pitch,roll\n"
          << "1,2,0.5,1.5,A,0,3,0,0,1,0.1,0,0,0,0,0\n";
    }
    const auto rows = outputs::readClosureTable(path);
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_NEAR(rows[0].measured.x(), 0.1, 1e-12);
    EXPECT_TRUE(rows[0].translationCovariance.array().isNaN().all());
    {
        std::ofstream f(path);  // neither width: named
        f << "from_node,to_node,from_time,to_time,source,match_id,score,strong,hypothesis,kept,"
             "x,y,z,yaw,pitch,roll\n"
          << "1,2,0.5,1.5,A,0,3,0,0,1,0.1,0,0,0,0,0,7\n";
    }
    try {
        outputs::readClosureTable(path);
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(path + ": line 2: 17 columns"), std::string::npos)
            << e.what();
    }
}

TEST(NodeTable, WhatIsWrittenReadsBackWithAnUntimedNode) {
    const std::string path = ::testing::TempDir() + "nodes_round_trip.csv";
    outputs::writeNodeTable(path, {{0, 10.5, 0, true, 1.25}, {1, 11.0, 1, false, std::nan("")}});
    const auto rows = outputs::readNodeTable(path);
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[1].node, 1);
    EXPECT_DOUBLE_EQ(rows[0].timestamp, 10.5);
    EXPECT_EQ(rows[1].segment, 1);
    EXPECT_TRUE(rows[0].keyframe);
    EXPECT_DOUBLE_EQ(rows[0].engineMs, 1.25);
    EXPECT_TRUE(std::isnan(rows[1].engineMs));
}

TEST(NodeTable, AShortLineNamesFileAndLine) {
    const std::string path = ::testing::TempDir() + "nodes_bad.csv";
    {
        std::ofstream f(path);
        f << "node,timestamp,segment,keyframe,engine_ms\n0,1.0,0,1,0.5\n1,2.0\n";
    }
    try {
        outputs::readNodeTable(path);
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(path + ": line 3"), std::string::npos) << e.what();
    }
}
