#include <gtest/gtest.h>
#include <lodestone/inspect/SensorExport.h>
#include <lodestone/obs/registerAllClasses.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "RawlogTestHelpers.h"
#include "SampleObservations.h"
#include "TestPaths.h"

using namespace lodestone;

namespace {
std::vector<std::string> lines(const std::string& file) {
    std::ifstream in(file);
    std::vector<std::string> out;
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
}
}  // namespace

class SensorExport : public ::testing::Test {
  protected:
    void SetUp() override {
        registerAllClasses();
        path_ = dir_.file("drive.rawlog");
        test::writeRawlog(path_, test::makeSampleDrive({1.0}));
    }
    test::TempDir dir_;
    std::string path_;
};

TEST_F(SensorExport, MagnetometerSeriesAsCsv) {
    const auto out = dir_.file("mag");
    const auto r = inspect::exportSensor(path_, "MAG_RIGHT", out);
    EXPECT_EQ(r.seriesRows, 101u);
    const auto rows = lines(r.seriesFile);
    ASSERT_EQ(rows.size(), 102u);
    EXPECT_EQ(rows[0].rfind("timestamp,MAG_X_uT,MAG_Y_uT,MAG_Z_uT", 0), 0u) << rows[0];
    // First sample: the robot at the origin heading +x, sensor 0.12 m to its right.
    std::istringstream first(rows[1]);
    std::vector<double> v;
    for (std::string cell; std::getline(first, cell, ',');) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 9u);
    EXPECT_NEAR(v[0], 1.7e9, 1e-3);
    EXPECT_NEAR(v[3], -44.0 + 25.0 * std::exp(-(1.0 + 1.12 * 1.12) / 0.5), 1e-6);
}

TEST_F(SensorExport, RgbdFramesAsPngWithRawDepth) {
    const auto out = dir_.file("rgbd");
    const auto r = inspect::exportSensor(path_, "RGBD", out);
    EXPECT_EQ(r.frames, 6u);
    const auto index = lines(r.framesIndex);
    ASSERT_EQ(index.size(), 7u);
    const cv::Mat depth = cv::imread(out + "/depth/000000.png", cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(depth.empty());
    EXPECT_EQ(depth.type(), CV_16UC1);
    const auto scan = test::makeRangeScan(0, 80, 60, 0);
    EXPECT_EQ(depth.at<uint16_t>(10, 40), scan->rangeImage(10, 40));
    EXPECT_EQ(depth.at<uint16_t>(0, 0), 0);  // invalid pixels stay 0
    const cv::Mat rgb = cv::imread(out + "/rgb/000000.png", cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(rgb.empty());
    EXPECT_EQ(rgb.type(), CV_8UC3);
    EXPECT_EQ(rgb.cols, 80);
}

TEST_F(SensorExport, UnknownLabelNamesTheLabelsPresent) {
    try {
        inspect::exportSensor(path_, "MAG_MIDDLE", dir_.file("none"));
        FAIL();
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("'MAG_MIDDLE'"), std::string::npos) << what;
        EXPECT_NE(what.find("'MAG_LEFT'"), std::string::npos) << what;
    }
}
