#include <gtest/gtest.h>
#include <lodestone/obs/ImuMagnetometerConversion.h>

#include "SampleObservations.h"

using namespace lodestone::obs;
using mrpt::obs::CObservationIMU;

TEST(ImuMagnetometerConversion, GaussImuBecomesMicrotesla) {
    auto imu = lodestone::test::makeImu(1.7e9, "XSENS", 2.0);
    imu->set(mrpt::obs::IMU_TEMPERATURE, 31.0);
    auto mag = magnetometerFromImu(*imu, MagneticUnit::gauss(), true, {0.1, 0.1, 0.1});
    EXPECT_EQ(mag->timestamp, imu->timestamp);
    EXPECT_EQ(mag->sensorLabel, "XSENS");
    EXPECT_EQ(mag->sensorPose, imu->sensorPose);
    EXPECT_NEAR(mag->field.x, 100.0 * imu->get(mrpt::obs::IMU_MAG_X), 1e-12);
    EXPECT_NEAR(mag->field.z, -44.0, 1e-12);
    ASSERT_TRUE(mag->temperature.has_value());
    EXPECT_DOUBLE_EQ(*mag->temperature, 31.0);
    EXPECT_TRUE(mag->calibrated);
    EXPECT_DOUBLE_EQ(mag->noiseStd.y, 0.1);
}

TEST(ImuMagnetometerConversion, XsensNormalizedUnitsScaleByLocalField) {
    CObservationIMU imu;
    imu.set(mrpt::obs::IMU_MAG_X, 0.5);
    imu.set(mrpt::obs::IMU_MAG_Y, -0.25);
    imu.set(mrpt::obs::IMU_MAG_Z, 1.0);
    auto mag = magnetometerFromImu(imu, MagneticUnit::xsensNormalized(48.0));
    EXPECT_DOUBLE_EQ(mag->field.x, 24.0);
    EXPECT_DOUBLE_EQ(mag->field.y, -12.0);
    EXPECT_DOUBLE_EQ(mag->field.z, 48.0);
    EXPECT_FALSE(mag->temperature.has_value());
}

TEST(ImuMagnetometerConversion, RoundTripThroughImuKeepsFieldPoseAndTemperature) {
    auto mag = lodestone::test::makeMagnetometer(1.7e9, "MAG", 4.0);
    for (const auto unit : {MagneticUnit::gauss(), MagneticUnit::xsensNormalized(50.0)}) {
        auto imu = imuFromMagnetometer(*mag, unit);
        EXPECT_TRUE(hasMagnetometerChannels(*imu));
        EXPECT_FALSE(imu->has(mrpt::obs::IMU_X_ACC));  // only what the magnetometer knows
        auto back = magnetometerFromImu(*imu, unit);
        EXPECT_EQ(back->timestamp, mag->timestamp);
        EXPECT_EQ(back->sensorPose, mag->sensorPose);
        EXPECT_NEAR(back->field.x, mag->field.x, 1e-12);
        EXPECT_NEAR(back->field.y, mag->field.y, 1e-12);
        EXPECT_NEAR(back->field.z, mag->field.z, 1e-12);
        EXPECT_EQ(back->temperature, mag->temperature);
    }
}

TEST(ImuMagnetometerConversion, ImuWithoutMagnetometerIsRejected) {
    CObservationIMU imu;
    imu.sensorLabel = "ACC_ONLY";
    imu.set(mrpt::obs::IMU_X_ACC, 1.0);
    imu.set(mrpt::obs::IMU_MAG_X, 1.0);  // X alone is not a field
    EXPECT_FALSE(hasMagnetometerChannels(imu));
    try {
        magnetometerFromImu(imu, MagneticUnit::gauss());
        FAIL() << "accepted an IMU without Y/Z magnetometer channels";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("ACC_ONLY"), std::string::npos);
    }
}
