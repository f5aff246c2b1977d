#include <lodestone/config/IniOverlay.h>
#include <lodestone/config/IniSection.h>

#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <algorithm>

using lodestone::config::IniOverlay;

namespace {
bool contains(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}
}  // namespace

TEST(IniOverlay, ItsKeysWinAndTheBaseIsReadThrough) {
    const mrpt::config::CConfigFileMemory base("[wheels]\nbase = 0.30\nradius = 0.04\n");
    IniOverlay overlay(base, "robot.ini");
    overlay.set("wheels", "base", 0.23);
    overlay.set("extra", "note", std::string("hello"));
    EXPECT_DOUBLE_EQ(overlay.read_double("wheels", "base", 0), 0.23);
    EXPECT_DOUBLE_EQ(overlay.read_double("wheels", "radius", 0), 0.04);
    EXPECT_EQ(overlay.read_string("extra", "note", ""), "hello");
    EXPECT_DOUBLE_EQ(base.read_double("wheels", "base", 0), 0.30);  // the base is untouched
    std::vector<std::string> sections, keys;
    overlay.getAllSections(sections);
    EXPECT_TRUE(contains(sections, "wheels") && contains(sections, "extra"));
    overlay.getAllKeys("wheels", keys);
    EXPECT_EQ(keys.size(), 2u);
    EXPECT_TRUE(overlay.keyExists("extra", "note"));
}

TEST(IniOverlay, ANumberReadsBackAsTheSameDouble) {
    const mrpt::config::CConfigFileMemory base("");
    IniOverlay overlay(base, "robot.ini");
    for (const double v : {0.23, 2578.33, 0.1 + 0.2, 1.0 / 3.0, 6.02214076e23}) {
        overlay.set("s", "k", v);
        EXPECT_EQ(overlay.read_double("s", "k", 0), v);
    }
}

TEST(IniOverlay, ErrorsNameItsSource) {
    const mrpt::config::CConfigFileMemory base("[wheels]\nbase = -1\n");
    IniOverlay overlay(base, "robot.ini");
    EXPECT_EQ(lodestone::config::sourceName(overlay), "robot.ini");
    lodestone::config::IniSection s(overlay, "wheels", lodestone::config::sourceName(overlay));
    try {
        s.fail("base", "must be > 0");
        FAIL() << "no error";
    } catch (const lodestone::config::ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("robot.ini [wheels] key 'base'"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(overlay.clear(), std::logic_error);
}
