#include <gtest/gtest.h>
#include <lodestone/config/IniSection.h>
#include <lodestone/sim/Scenario.h>

#include <filesystem>
#include <fstream>

#include "TestPaths.h"

using namespace lodestone::sim;

namespace {
const std::string kConfigDir = LODESTONE_CONFIG_INI_DIR;

std::string readFile(const std::string& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// office.ini with `from` replaced by `to` (appended when `from` is empty); returns the error
// message of loading it.
std::string loadError(const std::string& from, const std::string& to) {
    std::string text = readFile(kConfigDir + "/scenarios/office.ini");
    if (from.empty()) {
        text += to;
    } else {
        const auto at = text.find(from);
        if (at == std::string::npos) return "test bug: '" + from + "' not in office.ini";
        text.replace(at, from.size(), to);
    }
    lodestone::test::TempDir dir;
    const auto path = dir.file("edited.ini");
    std::ofstream(path) << text;
    try {
        Scenario::load(path);
    } catch (const lodestone::config::ConfigError& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(Scenario, EveryShippedScenarioLoads) {
    for (const char* name :
         {"office", "paper_loop", "paper_loop_qvga", "paper_kidnap", "paper_kidnap_unmapped",
          "corridor", "corridor_kidnap"}) {
        const auto path = kConfigDir + "/scenarios/" + name + ".ini";
        Scenario sc;
        ASSERT_NO_THROW(sc = Scenario::load(path)) << path;
        EXPECT_EQ(sc.name, name);
        EXPECT_EQ(sc.magnetometers.size(), 2u);
        EXPECT_GE(sc.motion.waypoints.size(), 4u);
    }
    const auto kidnap = Scenario::load(kConfigDir + "/scenarios/paper_kidnap.ini");
    EXPECT_EQ(kidnap.kidnaps.size(), 5u);
    const auto qvga = Scenario::load(kConfigDir + "/scenarios/paper_loop_qvga.ini");
    EXPECT_EQ(qvga.camera.width, 320);
    EXPECT_NEAR(qvga.camera.fx, 570.3 / 2, 1e-9);
}

TEST(Scenario, UnknownKeyIsNamed) {
    const auto msg = loadError("speed         = 0.4", "sped          = 0.4");
    EXPECT_NE(msg.find("[robot] key 'sped'"), std::string::npos) << msg;
}

TEST(Scenario, UnknownSectionIsNamed) {
    const auto msg = loadError("[camera]", "[camra]");
    EXPECT_NE(msg.find("[camra]"), std::string::npos) << msg;
}

TEST(Scenario, MalformedNumberIsNamed) {
    const auto msg = loadError("rate      = 30", "rate      = thirty");
    EXPECT_NE(msg.find("[camera] key 'rate'"), std::string::npos) << msg;
}

TEST(Scenario, PathThroughAWallNamesTheWaypoints) {
    const auto msg = loadError("waypoints = 1.2 1  3.8 1  3.8 3  1.2 3",
                               "waypoints = 1.2 1  3.8 1  6.0 3  1.2 3");
    EXPECT_NE(msg.find("waypoint 2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("waypoint 3"), std::string::npos) << msg;
    EXPECT_NE(msg.find("passes through a wall"), std::string::npos) << msg;
}

TEST(Scenario, PutDownInsideAWallNamesTheKidnap) {
    const auto msg = loadError("", "\n[kidnap]\nkidnap_1 = 5 2  5.0 2.0 0\n");
    EXPECT_NE(msg.find("kidnap_1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("inside a wall"), std::string::npos) << msg;
}

TEST(Scenario, BadSurfaceIsNamed) {
    const auto msg = loadError("wall_2 = bricks", "wall_2 = brick");
    EXPECT_NE(msg.find("key 'wall_2'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'brick'"), std::string::npos) << msg;
}

TEST(Scenario, TextureFilterIsPointOrArea) {
    EXPECT_EQ(loadError("texture_resolution = 200", "texture_resolution = 200\ntexture_filter = area"), "");
    const auto msg =
        loadError("texture_resolution = 200", "texture_resolution = 200\ntexture_filter = areas");
    EXPECT_NE(msg.find("key 'texture_filter'"), std::string::npos) << msg;
}

TEST(Scenario, NegativeNoiseAndHugeImagesAreNamed) {
    auto msg = loadError("noise_std = 0.3", "noise_std = -0.3");
    EXPECT_NE(msg.find("key 'noise_std'"), std::string::npos) << msg;
    msg = loadError("width     = 640", "width     = 100000");
    EXPECT_NE(msg.find("key 'width'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("4096"), std::string::npos) << msg;
}

TEST(Scenario, MissingFileIsNamed) {
    try {
        Scenario::load("/nonexistent/scenario.ini");
        FAIL();
    } catch (const lodestone::config::ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/scenario.ini"), std::string::npos);
    }
}

TEST(Scenario, CameraOverrideTakesWidthHeightAndRate) {
    CameraSpec cam;
    const int w = cam.width;
    EXPECT_TRUE(cam.override("320x240@15"));
    EXPECT_EQ(cam.width, 320);
    EXPECT_EQ(cam.height, 240);
    EXPECT_DOUBLE_EQ(cam.rate, 15);
    for (const char* bad : {"320x240", "8x8@15", "320x240@0", "320x240@15fps", "big",
                            "100000x100000@1", "640x480@1e6"}) {
        CameraSpec c;
        EXPECT_FALSE(c.override(bad)) << bad;
        EXPECT_EQ(c.width, w) << bad;
    }
}

TEST(Scenario, ImageFormatTakesPngJpgAndAQuality) {
    CameraSpec cam;
    EXPECT_EQ(cam.imageFormat, "png");  // lossless unless asked
    EXPECT_TRUE(cam.setImageFormat("jpg"));
    EXPECT_EQ(cam.imageFormat, "jpg");
    EXPECT_EQ(cam.jpegQuality, 90);
    EXPECT_TRUE(cam.setImageFormat("jpg:75"));
    EXPECT_EQ(cam.jpegQuality, 75);
    for (const char* bad : {"jpeg", "jpg:0", "jpg:101", "jpg:75x", "png:3", ""}) {
        CameraSpec c;
        EXPECT_FALSE(c.setImageFormat(bad)) << bad;
        EXPECT_EQ(c.imageFormat, "png") << bad;
    }
}

TEST(Scenario, AGyroSectionAddsAGyroAndItsKeysAreChecked) {
    EXPECT_FALSE(Scenario::load(kConfigDir + "/scenarios/office.ini").gyro) << "none unless asked";
    EXPECT_EQ(loadError("", "\n[gyro]\nrate = 200\nnoise_std_deg = 0.1\nbias_sigma_deg = 0\n"), "");
    EXPECT_NE(loadError("", "\n[gyro]\nnoise_std = 0.1\n").find("[gyro] key 'noise_std'"),
              std::string::npos);
    EXPECT_NE(loadError("", "\n[gyro]\nbias_sigma_deg = -1\n").find("bias_sigma_deg"),
              std::string::npos);
    EXPECT_NE(loadError("", "\n[gyro]\nrate = 0\n").find("rate"), std::string::npos);
}
