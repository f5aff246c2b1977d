// lodestone-view run in-process: screenshots and exports of a run's folder, usage, bad input,
// no display.
#include <ViewApp.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "RunFolder.h"
#include "TestPaths.h"

using namespace lodestone;

namespace {
int viewCmd(std::vector<std::string> args, std::string& out, std::string& err) {
    args.insert(args.begin(), "lodestone-view");
    std::vector<const char*> argv;
    for (const auto& a : args) argv.push_back(a.c_str());
    std::ostringstream o, e;
    const int code = view::runViewApp(static_cast<int>(argv.size()), argv.data(), o, e);
    out = o.str();
    err = e.str();
    return code;
}
}  // namespace

TEST(ViewApp, WritesAScreenshotAndAScene) {
    test::TempDir dir;
    test::writeRunFolder(dir.path().string(), true);
    std::string out, err;
    const int code = viewCmd({dir.path().string(), "--screenshot", dir.file("shot.png"), "--size", "400x300",
                              "--export", dir.file("run.3Dscene")},
                             out, err);
    if (code == 1 && err.find("off-screen") != std::string::npos)
        GTEST_SKIP() << "no off-screen OpenGL here: " << err;
    ASSERT_EQ(code, 0) << err;
    const cv::Mat shot = cv::imread(dir.file("shot.png"));
    EXPECT_EQ(shot.cols, 400);
    EXPECT_EQ(shot.rows, 300);
    EXPECT_GT(test::readTextFile(dir.file("run.3Dscene")).size(), 1000u);
}

TEST(ViewApp, UsageAndBadInputAreNamed) {
    test::TempDir dir;
    std::string out, err;
    EXPECT_EQ(viewCmd({}, out, err), 2);
    EXPECT_EQ(viewCmd({dir.path().string(), "--screenshot", dir.file("a.png"), "--size", "big"}, out, err), 2);
    EXPECT_NE(err.find("--size"), std::string::npos) << err;
    // An empty folder: graph.graph is named.
    EXPECT_EQ(viewCmd({dir.path().string(), "--export", dir.file("a.3Dscene")}, out, err), 1);
    EXPECT_NE(err.find("graph.graph"), std::string::npos) << err;
    test::writeRunFolder(dir.path().string(), false);
    EXPECT_EQ(viewCmd({dir.path().string(), "--export", dir.file("a.3Dscene"), "--camera", "1,x"}, out, err), 1);
    EXPECT_NE(err.find("camera '1,x'"), std::string::npos) << err;
    // Outputs that cannot be written are named.
    EXPECT_EQ(viewCmd({dir.path().string(), "--export", dir.file("no/such/folder/a.3Dscene")}, out, err), 1);
    EXPECT_NE(err.find("no/such/folder/a.3Dscene"), std::string::npos) << err;
    const int shot = viewCmd({dir.path().string(), "--screenshot", dir.file("no/such/folder/a.png")}, out, err);
    if (err.find("off-screen") == std::string::npos) {
        EXPECT_EQ(shot, 1);
        EXPECT_NE(err.find("no/such/folder/a.png"), std::string::npos) << err;
    }
    // A map folder whose manifest is damaged: the file is named.
    test::TempDir map;
    std::ofstream(map.file("manifest.ini")) << "[map]\nformat_version = banana\n";
    EXPECT_EQ(viewCmd({map.path().string(), "--export", dir.file("b.3Dscene")}, out, err), 1);
    EXPECT_NE(err.find("manifest.ini"), std::string::npos) << err;
}

TEST(ViewApp, TheWindowWithoutADisplaySaysSo) {
    test::TempDir dir;
    test::writeRunFolder(dir.path().string(), false);
    const char* display = std::getenv("DISPLAY");
    const std::string saved = display ? display : "";
    unsetenv("DISPLAY");
    std::string out, err;
    const int code = viewCmd({dir.path().string()}, out, err);
    if (!saved.empty()) setenv("DISPLAY", saved.c_str(), 1);
    EXPECT_EQ(code, 1);
    EXPECT_NE(err.find("no display"), std::string::npos) << err;
    EXPECT_NE(err.find("--screenshot"), std::string::npos) << err;
}
