#include <gtest/gtest.h>
#include <lodestone/config/IniSection.h>
#include <mrpt/config/CConfigFileMemory.h>

using lodestone::config::ConfigError;
using lodestone::config::IniSection;

namespace {
mrpt::config::CConfigFileMemory ini(const std::string& text) {
    return mrpt::config::CConfigFileMemory(text);
}

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(IniSection, ReadsValuesWithDefaultsAndComments) {
    auto cfg = ini("[a]\nx = 1.5   ; metres\nn = 3\nflag = true\nname = hello # hi\nv = 1 2 3\n");
    IniSection s(cfg, "a", "test.ini");
    EXPECT_DOUBLE_EQ(s.getDouble("x", 0), 1.5);
    EXPECT_EQ(s.getInt("n", 0), 3);
    EXPECT_TRUE(s.getBool("flag", false));
    EXPECT_EQ(s.getString("name", ""), "hello");
    EXPECT_EQ(s.getDoubles("v", {}, 3), (std::vector<double>{1, 2, 3}));
    EXPECT_DOUBLE_EQ(s.getDouble("absent", 7.0), 7.0);
    EXPECT_NO_THROW(s.finish());
}

TEST(IniSection, TypoedKeyIsNamed) {
    auto cfg = ini("[robot]\nspeed = 0.3\nsped = 0.4\n");
    IniSection s(cfg, "robot", "test.ini");
    s.getDouble("speed", 0);
    const auto msg = errorOf([&] { s.finish(); });
    EXPECT_NE(msg.find("test.ini [robot] key 'sped'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("speed"), std::string::npos) << msg;  // says what the section takes
}

TEST(IniSection, MalformedValuesAreRejected) {
    auto cfg = ini("[a]\nx = 0.3m\nn = 2.5\nb = maybe\nv = 1 2\n");
    IniSection s(cfg, "a", "f.ini");
    EXPECT_NE(errorOf([&] { s.getDouble("x", 0); }).find("key 'x'"), std::string::npos);
    EXPECT_NE(errorOf([&] { s.getInt("n", 0); }).find("integer"), std::string::npos);
    EXPECT_NE(errorOf([&] { s.getBool("b", false); }).find("'maybe'"), std::string::npos);
    EXPECT_NE(errorOf([&] { s.getDoubles("v", {}, 3); }).find("expected 3 numbers"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { s.requireDouble("missing"); }).find("missing"), std::string::npos);
}

TEST(IniSection, UnknownSectionIsNamed) {
    auto cfg = ini("[camera]\nrate = 30\n[camra]\nrate = 15\n");
    const auto msg = errorOf([&] {
        lodestone::config::checkSections(cfg, {"camera", "robot"}, "s.ini");
    });
    EXPECT_NE(msg.find("[camra]"), std::string::npos) << msg;
}

TEST(IniSection, PrefixedKeysInFileOrderAreKnown) {
    auto cfg = ini("[w]\nwall_1 = a\nwall_2 = b\nother = 1\n");
    IniSection s(cfg, "w", "f.ini");
    EXPECT_EQ(s.keysWithPrefix("wall_").size(), 2u);
    s.getInt("other", 0);
    EXPECT_NO_THROW(s.finish());
}
