// The 7-Scenes / 3DMatch importer: a folder the test builds (frames out of order on disk, a
// pixel with no depth, a frame without a pose, the camera matrix beside), the real 3DMatch
// frames in ../shared/data/rgbd/3dmatch (skipped when absent), and bad input named.
#include <gtest/gtest.h>
#include <ImportApp.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/datasets/SevenScenesImport.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "TestPaths.h"

using namespace lodestone;
namespace fs = std::filesystem;

namespace {
// Frame k: depth (1 + k) m in millimetres, one pixel 65535 (no depth); the pose a translation
// of k * 0.1 m along x, written as 7-Scenes does (4 x 4, row-major).
void writeFrame(const fs::path& seq, int k, bool withPose = true) {
    char stem[32];
    std::snprintf(stem, sizeof(stem), "frame-%06d", k);
    cv::imwrite((seq / (std::string(stem) + ".color.png")).string(), cv::Mat3b(24, 32, cv::Vec3b(20, 40, 60)));
    cv::Mat1w d(24, 32, static_cast<uint16_t>(1000 * (1 + k)));
    d(0, 0) = 65535;
    cv::imwrite((seq / (std::string(stem) + ".depth.png")).string(), d);
    if (withPose) {
        std::ofstream(seq / (std::string(stem) + ".pose.txt"))
            << "1 0 0 " << 0.1 * k << "\n0 1 0 0\n0 0 1 0\n0 0 0 1\n";
    }
}

int runApp(std::vector<std::string> args, std::ostringstream& o, std::ostringstream& e) {
    args.insert(args.begin(), {"lodestone-import", "7scenes"});
    std::vector<const char*> argv;
    for (const auto& a : args) argv.push_back(a.c_str());
    return datasets::runImportApp(static_cast<int>(argv.size()), argv.data(), o, e);
}
}  // namespace

TEST(SevenScenesImport, FramesInIndexOrderDepthInMetresPosesAsGroundTruth) {
    registerAllClasses();
    test::TempDir dir;
    const auto seq = dir.path() / "seq-01";
    fs::create_directories(seq);
    for (int k : {2, 0, 1}) writeFrame(seq, k, k != 1);
    std::ofstream(dir.path() / "camera-intrinsics.txt") << "570 0 321\n0 571 239\n0 0 1\n";
    const std::string out = dir.file("s.rawlog");
    std::ostringstream o, e;
    ASSERT_EQ(runApp({seq.string(), out}, o, e), 0) << e.str();
    EXPECT_NE(o.str().find("camera-intrinsics.txt"), std::string::npos) << o.str();
    io::RawlogSource source(out);
    int k = 0;
    while (auto obs = source.next()) {
        auto s = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs);
        ASSERT_TRUE(s);
        EXPECT_NEAR(mrpt::Clock::toDouble(s->timestamp), k / 30.0, 1e-6);
        EXPECT_NEAR(s->rangeImage(10, 10) * s->rangeUnits, 1.0 + k, 1e-6);  // mm -> m
        EXPECT_EQ(s->rangeImage(0, 0), 0);                                 // 65535: no depth
        EXPECT_NEAR(s->cameraParams.fx(), 570, 1e-9);
        EXPECT_NEAR(s->cameraParams.cy(), 239, 1e-9);
        ++k;
    }
    EXPECT_EQ(k, 3);
    const auto gt = io::readTumTrajectory(dir.file("s.gt.tum"));
    ASSERT_EQ(gt.size(), 2u);  // frame 1 has no pose
    EXPECT_NEAR(gt[1].timestamp, 2 / 30.0, 1e-6);
    EXPECT_NEAR(gt[1].pose.x(), 0.2, 1e-9);
}

TEST(SevenScenesImport, RealThreeDMatchFrames) {
    const fs::path seq = test::sharedDataDir() / "rgbd" / "3dmatch" / "seq-01";
    if (!fs::exists(seq)) GTEST_SKIP() << "real data folder absent: " << seq;
    registerAllClasses();
    test::TempDir dir;
    const auto r = datasets::importSevenScenes(seq.string(), dir.file("m.rawlog"), {});
    EXPECT_EQ(r.frames, 5u);
    EXPECT_EQ(r.groundTruthPoses, 5u);
    EXPECT_NEAR(r.intrinsics.fx, 570.342, 1e-3);  // the dataset's camera-intrinsics.txt
    io::RawlogSource source(dir.file("m.rawlog"));
    auto s = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(source.next());
    ASSERT_TRUE(s);
    // Indoor Kinect depth: the middle pixel between 0.3 and 6 m.
    const double middle = s->rangeImage(240, 320) * s->rangeUnits;
    EXPECT_GT(middle, 0.3);
    EXPECT_LT(middle, 6.0);
}

TEST(SevenScenesImport, BadInputIsNamed) {
    test::TempDir dir;
    const auto seq = dir.path() / "seq";
    fs::create_directories(seq);
    std::ostringstream o, e;
    EXPECT_EQ(runApp({seq.string(), dir.file("x.rawlog")}, o, e), 1);  // no frames
    EXPECT_NE(e.str().find("no frame-NNNNNN.color.png"), std::string::npos) << e.str();
    writeFrame(seq, 0);
    std::ofstream(seq / "frame-000000.pose.txt") << "1 0 0 0\n0 1 0 zero\n";
    std::ostringstream o2, e2;
    EXPECT_EQ(runApp({seq.string(), dir.file("x.rawlog")}, o2, e2), 1);
    EXPECT_NE(e2.str().find("frame-000000.pose.txt"), std::string::npos) << e2.str();
    fs::remove(seq / "frame-000000.depth.png");
    std::ostringstream o3, e3;
    EXPECT_EQ(runApp({seq.string(), dir.file("x.rawlog")}, o3, e3), 1);
    EXPECT_NE(e3.str().find("frame-000000.depth.png"), std::string::npos) << e3.str();
    std::ostringstream o4, e4;
    EXPECT_EQ(runApp({seq.string(), dir.file("x.rawlog"), "--intrinsics", "585,585"}, o4, e4), 2);
    EXPECT_NE(e4.str().find("--intrinsics"), std::string::npos) << e4.str();
}
