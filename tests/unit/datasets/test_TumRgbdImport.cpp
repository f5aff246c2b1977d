// The TUM RGB-D importer on TUM-layout folders the tests build: from the real Kinect frames of
// ../shared/data/rgbd/3dmatch (skipped when absent) and from the simulator.
#include <gtest/gtest.h>
#include <ImportApp.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/datasets/TumRgbdImport.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/math/CQuaternion.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "TestPaths.h"

using namespace lodestone;
namespace fs = std::filesystem;

namespace {
const fs::path k3dMatch = test::sharedDataDir() / "rgbd" / "3dmatch";

// A TUM-layout sequence from 3DMatch frames: depth rescaled from mm to 1/5000 m, colour copied
// into the temp folder (never into the repository), poses as groundtruth.txt.
void makeTumFromRealFrames(const fs::path& seq, const std::vector<int>& frames) {
    fs::create_directories(seq / "rgb");
    fs::create_directories(seq / "depth");
    std::ofstream rgb(seq / "rgb.txt"), depth(seq / "depth.txt"), gt(seq / "groundtruth.txt");
    rgb << "# colour images\n";
    depth << "# depth images\n";
    gt << "# timestamp tx ty tz qx qy qz qw\n";
    for (std::size_t k = 0; k < frames.size(); ++k) {
        char name[64];
        std::snprintf(name, sizeof(name), "seq-01/frame-%06d", frames[k]);
        const double t = 100.0 + 0.033 * k;
        char stamp[32];
        std::snprintf(stamp, sizeof(stamp), "%.6f", t);
        fs::copy_file(k3dMatch / (std::string(name) + ".color.png"),
                      seq / "rgb" / (std::string(stamp) + ".png"));
        cv::Mat mm = cv::imread((k3dMatch / (std::string(name) + ".depth.png")).string(),
                                cv::IMREAD_UNCHANGED);
        cv::Mat tum;
        mm.convertTo(tum, CV_16U, 5.0);  // mm -> 1/5000 m
        cv::imwrite((seq / "depth" / (std::string(stamp) + ".png")).string(), tum);
        // Depth a few ms after colour, as in the TUM recordings.
        char dstamp[32];
        std::snprintf(dstamp, sizeof(dstamp), "%.6f", t + 0.004);
        rgb << stamp << " rgb/" << stamp << ".png\n";
        depth << dstamp << " depth/" << stamp << ".png\n";
        std::ifstream pose(k3dMatch / (std::string(name) + ".pose.txt"));
        Eigen::Matrix4d m;
        for (int r = 0; r < 4; ++r) {
            for (int c = 0; c < 4; ++c) pose >> m(r, c);
        }
        const Eigen::Quaterniond q(Eigen::Matrix3d(m.block<3, 3>(0, 0)));
        gt << stamp << " " << m(0, 3) << " " << m(1, 3) << " " << m(2, 3) << " " << q.x() << " "
           << q.y() << " " << q.z() << " " << q.w() << "\n";
    }
}
}  // namespace

TEST(TumRgbdImport, RealKinectFramesInTumLayout) {
    if (!fs::exists(k3dMatch)) GTEST_SKIP() << "real data absent: " << k3dMatch;
    registerAllClasses();
    test::TempDir dir;
    const auto seq = dir.path() / "seq";
    makeTumFromRealFrames(seq, {0, 1, 2, 116, 422});
    std::ofstream(seq / "rgb.txt", std::ios::app) << "200.0 rgb/unpaired.png\n";  // no depth

    datasets::TumImportOptions o;
    o.intrinsics = datasets::TumIntrinsics::parse("570.342205,570.342205,320,240");
    const auto r = datasets::importTumRgbd(seq.string(), dir.file("out.rawlog"), o);
    EXPECT_EQ(r.frames, 5u);
    EXPECT_EQ(r.unmatchedRgb, 1u);
    EXPECT_EQ(r.groundTruthPoses, 5u);

    io::RawlogSource source(r.rawlog);
    const cv::Mat mm0 =
        cv::imread((k3dMatch / "seq-01/frame-000000.depth.png").string(), cv::IMREAD_UNCHANGED);
    std::size_t n = 0;
    while (auto obs = source.next()) {
        auto s = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs);
        ASSERT_TRUE(s);
        s->load();  // colour read in place from the sequence folder
        EXPECT_EQ(s->intensityImage.getWidth(), 640u);
        EXPECT_NEAR(s->cameraParams.fx(), 570.342205, 1e-9);
        if (n == 0) {
            // Depth in metres survives the 1/5000 m units exactly.
            for (const auto& [y, x] : {std::pair{240, 320}, {100, 500}, {400, 50}}) {
                EXPECT_NEAR(s->rangeImage(y, x) * s->rangeUnits, mm0.at<uint16_t>(y, x) / 1000.0,
                            1e-6);
            }
        }
        ++n;
    }
    EXPECT_EQ(n, 5u);
    const auto gt = io::readTumTrajectory(r.groundTruth);
    ASSERT_EQ(gt.size(), 5u);
    EXPECT_NEAR(gt[0].pose.x(), 1.973046, 1e-5);
}

TEST(TumRgbdImport, SyntheticSequenceThroughTheApp) {
    registerAllClasses();
    test::TempDir dir;
    const auto seq = dir.path() / "sim";
    fs::create_directories(seq / "rgb");
    fs::create_directories(seq / "depth");
    std::ofstream rgb(seq / "rgb.txt"), depth(seq / "depth.txt");
    for (int k = 0; k < 3; ++k) {
        cv::Mat3b colour(48, 64, cv::Vec3b(40 * k, 80, 160));
        cv::Mat1w d(48, 64, static_cast<uint16_t>(5000 * (1.0 + k)));  // 1, 2, 3 m
        const std::string name = std::to_string(k) + ".png";
        cv::imwrite((seq / "rgb" / name).string(), colour);
        cv::imwrite((seq / "depth" / name).string(), d);
        rgb << 10 + k << " rgb/" << name << "\n";
        depth << 10 + k + 0.01 << " depth/" << name << "\n";
    }
    rgb.close();
    depth.close();
    const std::string out = dir.file("sim.rawlog.gz");
    std::vector<std::string> args = {"lodestone-import", "tum", seq.string(), out,
                                     "--intrinsics",     "fr2"};
    std::vector<const char*> argv;
    for (const auto& a : args) argv.push_back(a.c_str());
    std::ostringstream o, e;
    ASSERT_EQ(datasets::runImportApp(static_cast<int>(argv.size()), argv.data(), o, e), 0) << e.str();
    io::RawlogSource source(out);
    int k = 0;
    while (auto obs = source.next()) {
        auto s = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs);
        ASSERT_TRUE(s);
        EXPECT_NEAR(s->rangeImage(10, 10) * s->rangeUnits, 1.0 + k, 1e-6);
        EXPECT_NEAR(s->cameraParams.fx(), 520.9, 1e-9);  // fr2
        ++k;
    }
    EXPECT_EQ(k, 3);
    EXPECT_FALSE(fs::exists(dir.file("sim.gt.tum")));  // no groundtruth.txt, none written
}

TEST(TumRgbdImport, DepthScale1000GivesMetres) {
    // ICL-NUIM / 7-Scenes style depth (millimetres) in a TUM layout: --depth-scale 1000.
    registerAllClasses();
    test::TempDir dir;
    const auto seq = dir.path() / "mm";
    fs::create_directories(seq / "rgb");
    fs::create_directories(seq / "depth");
    cv::imwrite((seq / "rgb" / "0.png").string(), cv::Mat3b(24, 32, cv::Vec3b(10, 20, 30)));
    cv::imwrite((seq / "depth" / "0.png").string(), cv::Mat1w(24, 32, static_cast<uint16_t>(1500)));
    std::ofstream(seq / "rgb.txt") << "5.0 rgb/0.png\n";
    std::ofstream(seq / "depth.txt") << "5.001 depth/0.png\n";
    const std::string out = dir.file("mm.rawlog");
    for (const auto& [scale, metres] : {std::pair<std::string, double>{"1000", 1.5}, {"5000", 0.3}}) {
        std::vector<std::string> args = {"lodestone-import", "tum", seq.string(), out, "--depth-scale", scale};
        std::vector<const char*> argv;
        for (const auto& a : args) argv.push_back(a.c_str());
        std::ostringstream o, e;
        ASSERT_EQ(datasets::runImportApp(static_cast<int>(argv.size()), argv.data(), o, e), 0) << e.str();
        io::RawlogSource source(out);
        auto s = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(source.next());
        ASSERT_TRUE(s);
        EXPECT_NEAR(s->rangeImage(5, 5) * s->rangeUnits, metres, 1e-6) << "--depth-scale " << scale;
    }
    // A scale that is no scale is a usage error (2), naming the option.
    std::vector<std::string> args = {"lodestone-import", "tum", seq.string(), out, "--depth-scale", "0"};
    std::vector<const char*> argv;
    for (const auto& a : args) argv.push_back(a.c_str());
    std::ostringstream o, e;
    EXPECT_EQ(datasets::runImportApp(static_cast<int>(argv.size()), argv.data(), o, e), 2);
    EXPECT_NE(e.str().find("--depth-scale"), std::string::npos) << e.str();
}

TEST(TumRgbdImport, BadInputIsNamed) {
    test::TempDir dir;
    std::ofstream(dir.file("rgb.txt")) << "1.0 rgb/a.png\nnot-a-time rgb/b.png\n";
    std::ofstream(dir.file("depth.txt")) << "1.0 depth/a.png\n";
    try {
        datasets::importTumRgbd(dir.path().string(), dir.file("o.rawlog"), {});
        FAIL();
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("rgb.txt: line 2"), std::string::npos) << e.what();
    }
    EXPECT_THROW(datasets::TumIntrinsics::parse("fr4"), std::invalid_argument);
    EXPECT_THROW(datasets::importTumRgbd(dir.file("nowhere"), dir.file("o.rawlog"), {}),
                 std::runtime_error);
}
