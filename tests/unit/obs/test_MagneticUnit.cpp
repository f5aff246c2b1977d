#include <gtest/gtest.h>
#include <lodestone/obs/MagneticUnit.h>

using lodestone::obs::MagneticUnit;

TEST(MagneticUnit, ParsesKnownUnits) {
    EXPECT_DOUBLE_EQ(MagneticUnit::parse("gauss").microteslaPerUnit, 100.0);
    EXPECT_DOUBLE_EQ(MagneticUnit::parse("uT").microteslaPerUnit, 1.0);
    EXPECT_DOUBLE_EQ(MagneticUnit::parse("T").microteslaPerUnit, 1e6);
    EXPECT_DOUBLE_EQ(MagneticUnit::parse("xsens:48.5").microteslaPerUnit, 48.5);
}

TEST(MagneticUnit, RejectsTyposWithTheTextInTheMessage) {
    for (const char* bad : {"gaus", "", "xsens:", "xsens:abc", "xsens:-3", "xsens:50uT"}) {
        try {
            MagneticUnit::parse(bad);
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(std::string("'") + bad + "'"), std::string::npos)
                << e.what();
        }
    }
}
