// Depth-to-colour registration on import: geometry against the pinhole model (a shifted depth
// camera moves a near patch further than the wall behind it and the patch hides the wall), a
// different depth grid, the pose parser, and the importer's two options.
#include <gtest/gtest.h>
#include <lodestone/datasets/DepthRegistration.h>
#include <ImportApp.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "TestPaths.h"

using namespace lodestone;
namespace fs = std::filesystem;

namespace {
datasets::PinholeIntrinsics intrinsics(double f, double cx, double cy) {
    datasets::PinholeIntrinsics k;
    k.fx = k.fy = f;
    k.cx = cx;
    k.cy = cy;
    return k;
}

// A wall at 2 m with a 20 x 20 px patch at 1 m (values in millimetres).
cv::Mat1w wallWithPatch(int cols, int rows, int patchU, int patchV) {
    cv::Mat1w d(rows, cols, static_cast<std::uint16_t>(2000));
    d(cv::Rect(patchU, patchV, 20, 20)).setTo(1000);
    return d;
}

int runImport(const std::vector<std::string>& args, std::string* error = nullptr) {
    std::vector<const char*> argv;
    for (const auto& a : args) argv.push_back(a.c_str());
    std::ostringstream o, e;
    const int code = datasets::runImportApp(static_cast<int>(argv.size()), argv.data(), o, e);
    if (error) *error = e.str();
    return code;
}
}  // namespace

TEST(DepthRegistration, IdentityLeavesDepthAsItIs) {
    const auto k = intrinsics(525, 319.5, 239.5);
    datasets::DepthRegistration r;
    r.depth = k;
    cv::Mat1w d = wallWithPatch(640, 480, 300, 200);
    d(10, 10) = 0;       // no depth stays no depth
    d(11, 11) = 65535;   // nor does "invalid"
    const cv::Mat out = datasets::registerDepthToColour(d, r, k, d.size(), 1000.0);
    cv::Mat1w expected = d.clone();
    expected(11, 11) = 0;
    EXPECT_EQ(cv::norm(out, expected, cv::NORM_INF), 0.0);
}

TEST(DepthRegistration, ABaselineShiftsNearThingsMoreAndTheyHideTheWall) {
    // The depth camera 2.5 cm to the colour camera's +x (a Kinect's baseline): a point at depth
    // z moves f * 0.025 / z pixels to the right in colour - 6.6 px at 2 m, 13.1 px at 1 m.
    const auto k = intrinsics(525, 319.5, 239.5);
    datasets::DepthRegistration r;
    r.depth = k;
    r.colourFromDepth.translation() = Eigen::Vector3d(0.025, 0, 0);
    const cv::Mat1w d = wallWithPatch(640, 480, 300, 200);
    const cv::Mat1w out = datasets::registerDepthToColour(d, r, k, d.size(), 1000.0);
    // The patch's columns 300..319 land on 313..332 (13.125 px, rounded); the wall's on
    // u + 6.6. Where both land, the patch (1 m) wins over the wall behind it.
    for (int v = 205; v < 215; ++v) {
        EXPECT_EQ(out(v, 314), 1000) << v;
        EXPECT_EQ(out(v, 331), 1000) << v;
        EXPECT_EQ(out(v, 333), 2000) << v;  // the wall again past the patch's right edge
        EXPECT_EQ(out(v, 305), 2000) << v;  // and left of it (the wall shifted 6.6 px) ...
        EXPECT_EQ(out(v, 310), 0) << v;     // ... but for the wall the depth camera could not
                                            // see behind the patch: colour 307..312, a shadow
    }
    // The wall's left edge: colour columns 0..6 see nothing from the depth camera.
    EXPECT_EQ(out(100, 3), 0);
    EXPECT_EQ(out(100, 10), 2000);
    // Depth is the colour camera's z: unchanged by a sideways baseline.
    EXPECT_EQ(out(400, 400), 2000);
}

TEST(DepthRegistration, DepthOnACoarserGridLandsOnColourPixels) {
    // QVGA depth (f 262.5) into VGA colour (f 525), no baseline: depth pixel (u, v) lands on
    // colour (2u + 0.5, 2v + 0.5) - every other colour pixel gets a value.
    const auto kc = intrinsics(525, 319.5, 239.5);
    datasets::DepthRegistration r;
    r.depth = intrinsics(262.5, 159.5, 119.5);
    const cv::Mat1w d(240, 320, static_cast<std::uint16_t>(1500));
    const cv::Mat1w out = datasets::registerDepthToColour(d, r, kc, cv::Size(640, 480), 1000.0);
    EXPECT_EQ(out.size(), cv::Size(640, 480));
    const int filled = cv::countNonZero(out);
    EXPECT_NEAR(filled, 320 * 240, 2 * 320 + 2 * 240);  // one colour pixel per depth pixel
    EXPECT_EQ(out(241, 321), 1500);
}

TEST(DepthRegistration, PoseParserNamesBadText) {
    const auto T = datasets::DepthRegistration::parsePose("0.025,0,0,0,0,0,2");  // normalized
    EXPECT_NEAR(T.translation().x(), 0.025, 1e-12);
    EXPECT_TRUE(T.linear().isApprox(Eigen::Matrix3d::Identity()));
    for (const char* bad : {"0,0,0,0,0,0,0", "1,2,3", "0,0,0,0,0,0,1,5", "a,0,0,0,0,0,1",
                            "nan,0,0,0,0,0,1", "0 0 0 0 0 0 1"}) {
        try {
            datasets::DepthRegistration::parsePose(bad);
            ADD_FAILURE() << bad;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
        }
    }
}

TEST(DepthRegistration, ImporterRegistersOnRequest) {
    registerAllClasses();
    test::TempDir dir;
    const auto seq = dir.path() / "raw";
    fs::create_directories(seq / "rgb");
    fs::create_directories(seq / "depth");
    cv::imwrite((seq / "rgb" / "0.png").string(), cv::Mat3b(480, 640, cv::Vec3b(10, 20, 30)));
    cv::imwrite((seq / "depth" / "0.png").string(), cv::Mat1w(240, 320, static_cast<std::uint16_t>(1500)));
    std::ofstream(seq / "rgb.txt") << "5.0 rgb/0.png\n";
    std::ofstream(seq / "depth.txt") << "5.001 depth/0.png\n";
    const std::string out = dir.file("reg.rawlog");
    ASSERT_EQ(runImport({"lodestone-import", "tum", seq.string(), out, "--depth-scale", "1000",
                         "--intrinsics", "525,525,319.5,239.5", "--depth-intrinsics",
                         "262.5,262.5,159.5,119.5", "--depth-to-colour", "0,0,0,0,0,0,1"}),
              0);
    io::RawlogSource source(out);
    auto s = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(source.next());
    ASSERT_TRUE(s);
    EXPECT_EQ(s->rangeImage.cols(), 640);  // depth now on the colour grid
    EXPECT_EQ(s->cameraParams.ncols, 640u);
    EXPECT_NEAR(s->rangeImage(241, 321) * s->rangeUnits, 1.5, 1e-6);

    // One option without the other, or a bad pose: usage errors naming the option.
    std::string error;
    EXPECT_EQ(runImport({"lodestone-import", "tum", seq.string(), out, "--depth-intrinsics",
                         "262.5,262.5,159.5,119.5"},
                        &error),
              2);
    EXPECT_NE(error.find("--depth-to-colour"), std::string::npos) << error;
    EXPECT_EQ(runImport({"lodestone-import", "7scenes", seq.string(), out, "--depth-intrinsics",
                         "262.5,262.5,159.5,119.5", "--depth-to-colour", "0,0,0,0,0,0,0"},
                        &error),
              2);
    EXPECT_NE(error.find("--depth-to-colour"), std::string::npos) << error;
}
