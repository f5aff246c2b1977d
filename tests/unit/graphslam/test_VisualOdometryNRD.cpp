#include <gtest/gtest.h>
#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/nrd/VisualOdometryNRD.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <string>

using namespace lodestone;

TEST(VisualOdometryNRD, ConfigurationMistakesNameTheKey) {
    graphslam::VisualOdometryNRD nrd;
    const auto errorOf = [&](const std::string& text) {
        mrpt::config::CConfigFileMemory ini(text);
        try {
            nrd.configure(ini);
        } catch (const config::ConfigError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(errorOf("[VisualOdometryNRD]\nbridge_by_dept = true\nuse_gyro = true\n").find("bridge_by_dept"),
              std::string::npos);
    // The depth corrects the gyro's bridge: without a gyro there is none to correct.
    EXPECT_NE(errorOf("[VisualOdometryNRD]\nbridge_by_depth = true\n").find("needs use_gyro"),
              std::string::npos);
    EXPECT_NE(errorOf("[VisualOdometryNRD]\nuse_gyro = true\nbridge_speed_sigma = 0\n").find("bridge_speed_sigma"),
              std::string::npos);
    EXPECT_NE(errorOf("[VisualOdometryNRD]\nuse_gyro = true\nbridge_height_sigma = -1\n").find("bridge_height_sigma"),
              std::string::npos);
    EXPECT_EQ(errorOf("[VisualOdometryNRD]\nuse_gyro = true\nbridge_by_depth = true\n"), "no error");
    EXPECT_TRUE(nrd.params().bridgeByDepth);
}
