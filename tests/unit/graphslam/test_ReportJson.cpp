#include <lodestone/graphslam/ReportJson.h>

#include <gtest/gtest.h>

#include <cmath>

using lodestone::graphslam::JsonObject;

TEST(ReportJson, WritesNestedObjectsListsAndEscapes) {
    JsonObject inner;
    inner.set("n", 3).set("ok", true);
    JsonObject o;
    o.set("name", "a \"quoted\"\\path\n")
        .set("x", 0.25)
        .set("bad", std::nan(""))
        .set("list", std::vector<double>{1, 2.5})
        .set("inner", inner)
        .set("items", std::vector<JsonObject>{inner, JsonObject().set("k", "v")})
        .set("empty", std::vector<JsonObject>{});
    const std::string s = o.str();
    EXPECT_NE(s.find(R"("name": "a \"quoted\"\\path\n")"), std::string::npos) << s;
    EXPECT_NE(s.find(R"("x": 0.25)"), std::string::npos);
    EXPECT_NE(s.find(R"("bad": null)"), std::string::npos);
    EXPECT_NE(s.find(R"("list": [1, 2.5])"), std::string::npos);
    EXPECT_NE(s.find(R"("ok": true)"), std::string::npos);
    EXPECT_NE(s.find(R"("k": "v")"), std::string::npos);
    EXPECT_NE(s.find(R"("empty": [])"), std::string::npos);
    // Balanced braces and brackets: the structure closes.
    int braces = 0, brackets = 0;
    for (char c : s) {
        braces += c == '{' ? 1 : c == '}' ? -1 : 0;
        brackets += c == '[' ? 1 : c == ']' ? -1 : 0;
    }
    EXPECT_EQ(braces, 0);
    EXPECT_EQ(brackets, 0);
}

TEST(ReportJson, SettingAKeyAgainReplacesIt) {
    JsonObject o;
    o.set("a", 1).set("a", 2);
    EXPECT_EQ(o.str(), "{\n  \"a\": 2\n}");
}

TEST(ReportJson, EpochTimestampsKeepTheirMilliseconds) {
    // report.json carries relocation times; ten significant digits would round them to seconds.
    JsonObject o;
    o.set("t", 1700000511.533328);
    EXPECT_NE(o.str().find("1700000511.53333"), std::string::npos) << o.str();
}
