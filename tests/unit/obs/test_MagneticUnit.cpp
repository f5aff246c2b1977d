#include <gtest/gtest.h>
#include <lodestone/obs/MagneticUnit.h>

#include <cmath>

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

TEST(MagneticUnit, NormalizedUnitsCarryTheirFieldStrength) {
    EXPECT_DOUBLE_EQ(MagneticUnit::parse("normalized:48.5").microteslaPerUnit, 48.5);
    EXPECT_EQ(MagneticUnit::parse("normalized:48.5").name, "normalized:48.5");
    for (const char* bad : {"normalized:", "normalized:0", "normalized:x"}) {
        EXPECT_THROW(MagneticUnit::parse(bad), std::invalid_argument) << bad;
    }
}

TEST(MagneticUnit, EarthsFieldIsPlausibleOtherUnitsAreNotAndTheLikelyUnitIsNamed) {
    using lodestone::obs::implausibleFieldMagnitude;
    EXPECT_FALSE(implausibleFieldMagnitude({48, 52, 45, 60}));
    EXPECT_FALSE(implausibleFieldMagnitude({}));
    // A few wild readings (a steel door) do not decide: the median does.
    EXPECT_FALSE(implausibleFieldMagnitude({48, 52, 300, 0.1, 45, NAN}));
    const auto gauss = implausibleFieldMagnitude({0.48, 0.52, 0.45});
    ASSERT_TRUE(gauss);
    EXPECT_NE(gauss->find("0.48 uT"), std::string::npos) << *gauss;
    EXPECT_NE(gauss->find("as gauss they would be plausible"), std::string::npos) << *gauss;
    const auto normalized = implausibleFieldMagnitude({1.02, 0.98, 1.2});
    ASSERT_TRUE(normalized);
    EXPECT_NE(normalized->find("normalized units"), std::string::npos) << *normalized;
    const auto nano = implausibleFieldMagnitude({48000, 52000});
    ASSERT_TRUE(nano);
    EXPECT_NE(nano->find("nanotesla"), std::string::npos) << *nano;
    const auto tesla = implausibleFieldMagnitude({4.8e-5, 5.2e-5, 5e-5});
    ASSERT_TRUE(tesla);
    EXPECT_NE(tesla->find("as T they would be plausible"), std::string::npos) << *tesla;
}
