// Off-screen pictures of a run: the same picture byte for byte for a fixed camera, each
// closer's edges in its own colour, each segment's nodes in theirs; a .3Dscene MRPT reads back.
#include <lodestone/view/Palette.h>
#include <lodestone/view/SceneBuilder.h>
#include <lodestone/view/Snapshot.h>

#include <mrpt/opengl/COpenGLScene.h>

#include <gtest/gtest.h>

#include "RunFolder.h"
#include "TestPaths.h"

using namespace lodestone;

namespace {

/** Renders, or skips the test when this machine has no EGL context to render with. */
#define RENDER_OR_SKIP(image, scene, camera, w, h)                                    \
    mrpt::img::CImage image;                                                         \
    try {                                                                            \
        image = view::renderScene(scene, camera, w, h);                              \
    } catch (const std::runtime_error& e) {                                          \
        GTEST_SKIP() << "no off-screen OpenGL here: " << e.what();                   \
    }

/** The pixels nearer `colour` than the background or any other of the view's colours (lines
 * and points are blended into the background at their edges). */
std::size_t pixelsOf(const mrpt::img::CImage& image, const mrpt::img::TColor& colour) {
    const std::vector<mrpt::img::TColor> others{
        {102, 102, 102},  // MRPT's background
        view::closerColour("OrbSubmapERD"), view::closerColour("MagneticWindowERD"),
        view::refusedColour(), view::odometryColour(), view::segmentColour(0), view::segmentColour(1),
        view::segmentColour(2)};
    const auto distance = [](const std::uint8_t* bgr, const mrpt::img::TColor& c) {
        const int db = bgr[0] - c.B, dg = bgr[1] - c.G, dr = bgr[2] - c.R;
        return db * db + dg * dg + dr * dr;
    };
    std::size_t n = 0;
    for (unsigned y = 0; y < image.getHeight(); ++y)
        for (unsigned x = 0; x < image.getWidth(); ++x) {
            const auto* p = image.ptr<std::uint8_t>(x, y);  // (CImage keeps BGR)
            const int own = distance(p, colour);
            bool nearest = own < 40 * 40;
            for (const auto& o : others)
                if (!(o == colour) && distance(p, o) <= own) nearest = false;
            if (nearest) ++n;
        }
    return n;
}

view::SceneContent content(const test::TempDir& dir, bool truth = false) {
    test::writeRunFolder(dir.path().string(), truth);
    return view::readRunFolder(dir.path().string());
}

/** From straight above, every node in view. */
view::ViewCamera above(const view::SceneContent& c) {
    view::ViewCamera camera = view::framing(c);
    camera.elevationDeg = 90;
    return camera;
}

}  // namespace

TEST(Snapshot, AFixedCameraGivesTheSamePictureByteForByte) {
    test::TempDir dir;
    const auto c = content(dir, true);
    const auto scene = view::buildScene(c);
    RENDER_OR_SKIP(first, *scene, view::framing(c), 320, 240);
    view::writeScreenshot(*scene, view::framing(c), 320, 240, dir.file("a.png"));
    view::writeScreenshot(*view::buildScene(content(dir, true)), view::framing(c), 320, 240, dir.file("b.png"));
    const std::string a = test::readTextFile(dir.file("a.png")), b = test::readTextFile(dir.file("b.png"));
    EXPECT_GT(a.size(), 1000u);
    EXPECT_EQ(a, b);
    // Another camera, another picture.
    view::writeScreenshot(*scene, view::parseCamera("30,20", view::framing(c)), 320, 240, dir.file("c.png"));
    EXPECT_NE(a, test::readTextFile(dir.file("c.png")));
}

TEST(Snapshot, EachClosersEdgesAreInItsColourAndRefusedOnesInRed) {
    test::TempDir dir;
    const auto c = content(dir);
    view::Layers edgesOnly;
    edgesOnly.nodes = edgesOnly.odometry = edgesOnly.cloud = edgesOnly.truth = edgesOnly.floor = false;
    const auto scene = view::buildScene(c, edgesOnly);
    RENDER_OR_SKIP(image, *scene, above(c), 640, 480);
    EXPECT_GT(pixelsOf(image, view::closerColour("OrbSubmapERD")), 50u);
    EXPECT_GT(pixelsOf(image, view::closerColour("MagneticWindowERD")), 50u);
    EXPECT_GT(pixelsOf(image, view::refusedColour()), 50u);
    EXPECT_EQ(pixelsOf(image, view::odometryColour()), 0u);
    // Without the closures layer, none of their colours.
    edgesOnly.closures = edgesOnly.refused = false;
    edgesOnly.odometry = true;
    RENDER_OR_SKIP(odometry, *view::buildScene(c, edgesOnly), above(c), 640, 480);
    EXPECT_EQ(pixelsOf(odometry, view::closerColour("OrbSubmapERD")), 0u);
    EXPECT_GT(pixelsOf(odometry, view::odometryColour()), 50u);
}

TEST(Snapshot, TwoSegmentsAreTwoColours) {
    test::TempDir dir;
    const auto c = content(dir);
    view::Layers nodesOnly;
    nodesOnly.odometry = nodesOnly.closures = nodesOnly.refused = nodesOnly.cloud = nodesOnly.truth =
        nodesOnly.floor = false;
    RENDER_OR_SKIP(image, *view::buildScene(c, nodesOnly), above(c), 640, 480);
    // Ten nodes each, 4 px points.
    EXPECT_GE(pixelsOf(image, view::segmentColour(0)), 10u * 4);
    EXPECT_GE(pixelsOf(image, view::segmentColour(1)), 10u * 4);
    EXPECT_EQ(pixelsOf(image, view::segmentColour(2)), 0u);
}

TEST(Snapshot, AnExportedSceneIsReadBackByMrpt) {
    test::TempDir dir;
    const auto scene = view::buildScene(content(dir, true));
    ASSERT_TRUE(scene->saveToFile(dir.file("run.3Dscene")));
    mrpt::opengl::COpenGLScene read;
    ASSERT_TRUE(read.loadFromFile(dir.file("run.3Dscene")));
    EXPECT_EQ(view::layerNames(read), view::layerNames(*scene));
}

TEST(Snapshot, ACameraIsParsedOrNamedWhereItIsWrong) {
    const view::ViewCamera base;
    const auto c = view::parseCamera("10,20,30,1,2,3", base);
    EXPECT_EQ(c.azimuthDeg, 10);
    EXPECT_EQ(c.elevationDeg, 20);
    EXPECT_EQ(c.distance, 30);
    EXPECT_EQ(c.pointingAt[2], 3);
    EXPECT_EQ(view::parseCamera("5,6", base).distance, base.distance);
    for (const char* bad : {"", "1", "1,2,3,4", "a,2", "1,2,-3", "1,2,nan", "1,2x"})
        EXPECT_THROW(view::parseCamera(bad, base), std::invalid_argument) << bad;
}
