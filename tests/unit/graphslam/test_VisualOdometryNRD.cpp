#include <gtest/gtest.h>
#include <lodestone/graphslam/nrd/VisualOdometryNRD.h>

#include <string>

#include "ConfigErrorOf.h"

using namespace lodestone;

TEST(VisualOdometryNRD, ConfigurationMistakesNameTheKey) {
    graphslam::VisualOdometryNRD nrd;
    const auto errorOf = [&](const std::string& text) { return test::configErrorOf(nrd, text); };
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
    // Without a gyro the depth may measure the turn too - from the same frames' depth only.
    EXPECT_NE(errorOf("[VisualOdometryNRD]\nbridge_by_depth = false\nbridge_turn_by_depth = true\n")
                  .find("needs bridge_by_depth"),
              std::string::npos);
    EXPECT_NE(errorOf("[VisualOdometryNRD]\nbridge_by_depth = true\nbridge_turn_by_depth = true\n"
                      "bridge_tilt_sigma_deg = -1\n").find("bridge_tilt_sigma_deg"),
              std::string::npos);
    EXPECT_NE(errorOf("[VisualOdometryNRD]\nbridge_by_depth = true\nbridge_turn_by_depth = true\n"
                      "bridge_turn_max_sigma_deg = 0\n").find("bridge_turn_max_sigma_deg"),
              std::string::npos);
    EXPECT_EQ(errorOf("[VisualOdometryNRD]\nbridge_by_depth = true\nbridge_turn_by_depth = true\n"
                      "bridge_turn_rate_sigma_deg = 45\nbridge_tilt_sigma_deg = 3\n"),
              "no error");
    EXPECT_TRUE(nrd.params().bridgeTurnByDepth);
    EXPECT_NEAR(nrd.params().bridgeTurn.rate.speedSigma, 45 * M_PI / 180, 1e-12);
    EXPECT_NEAR(nrd.params().bridgeTurn.tiltSigma, 3 * M_PI / 180, 1e-12);
    // A carrier's level up, where no accelerometer measures one.
    EXPECT_NE(errorOf("[VisualOdometryNRD]\ncarrier_tilt_sigma_deg = -2\n").find("carrier_tilt_sigma_deg"),
              std::string::npos);
    EXPECT_EQ(errorOf("[VisualOdometryNRD]\ncarrier_tilt_sigma_deg = 4\n"), "no error");
    EXPECT_NEAR(nrd.params().carrierTiltSigma, 4 * M_PI / 180, 1e-12);
    EXPECT_NE(errorOf("[VisualOdometryNRD]\ncarrier_tilt_sigma_deg = 0\ncarrier_height_sigma = 0.05\n").find("needs use_gravity"),
              std::string::npos)
        << "a height with no up";
    EXPECT_NE(errorOf("[VisualOdometryNRD]\ncarrier_tilt_sigma_deg = 4\ncarrier_height_sigma = -1\n")
                  .find("carrier_height_sigma"),
              std::string::npos);
    EXPECT_EQ(errorOf("[VisualOdometryNRD]\ncarrier_tilt_sigma_deg = 4\ncarrier_height_sigma = 0.05\n"),
              "no error");
    EXPECT_EQ(nrd.params().carrierHeightSigma, 0.05);
}
