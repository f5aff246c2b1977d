// CMagnetometerFromImu around stand-in IMU drivers: the unit conversion, and a driver whose
// initialize() hangs (as CIMUXSens_MT4 does on a missing port).
#include <gtest/gtest.h>
#include <lodestone/drivers/CMagnetometerFromImu.h>
#include <lodestone/drivers/registerDrivers.h>
#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationIMU.h>

#include <chrono>
#include <thread>

namespace lodestone::test {

// An IMU that reports a field of (0.2, 0, -0.4) gauss, and every third reading without
// magnetometer channels (an IMU configured for the gyros only).
class CFakeImu : public mrpt::hwdrivers::CGenericSensor {
    DEFINE_GENERIC_SENSOR(CFakeImu)
  public:
    void doProcess() override {
        auto imu = mrpt::obs::CObservationIMU::Create();
        imu->timestamp = mrpt::Clock::now();
        imu->sensorLabel = "FAKE";
        if (++n_ % 3 != 0) {
            imu->set(mrpt::obs::IMU_MAG_X, 0.2);
            imu->set(mrpt::obs::IMU_MAG_Y, 0.0);
            imu->set(mrpt::obs::IMU_MAG_Z, -0.4);
        }
        imu->set(mrpt::obs::IMU_WZ, 0.1);
        appendObservation(imu);
    }

  protected:
    void loadConfig_sensorSpecific(const mrpt::config::CConfigFileBase&, const std::string&) override {}

  private:
    int n_{0};
};

// An IMU whose start never returns in time.
class CHangingImu : public mrpt::hwdrivers::CGenericSensor {
    DEFINE_GENERIC_SENSOR(CHangingImu)
  public:
    void initialize() override { std::this_thread::sleep_for(std::chrono::seconds(20)); }
    void doProcess() override {}

  protected:
    void loadConfig_sensorSpecific(const mrpt::config::CConfigFileBase&, const std::string&) override {}
};

}  // namespace lodestone::test

IMPLEMENTS_GENERIC_SENSOR(CFakeImu, lodestone::test)
IMPLEMENTS_GENERIC_SENSOR(CHangingImu, lodestone::test)

namespace {
mrpt::hwdrivers::CGenericSensor::Ptr wrapper(const std::string& ini) {
    lodestone::registerAllClasses();
    lodestone::drivers::registerDrivers();
    lodestone::test::CFakeImu::doRegister();
    lodestone::test::CHangingImu::doRegister();
    auto s = mrpt::hwdrivers::CGenericSensor::createSensorPtr("CMagnetometerFromImu");
    mrpt::config::CConfigFileMemory config(ini);
    s->loadConfig(config, "MAG");
    return s;
}
}  // namespace

TEST(CMagnetometerFromImu, IMUMagnetometerChannelsBecomeMicrotesla) {
    auto s = wrapper("[MAG]\nsensorLabel = MAG\nimu_driver = CFakeImu\nimu_section = IMU\nunit = gauss\n"
                     "noise_std_uT = 0.3\n[IMU]\n");
    s->initialize();
    std::vector<lodestone::obs::CObservationMagnetometer::Ptr> got;
    const auto take = [&] {
        s->doProcess();
        for (auto& [t, o] : s->getObservations()) {
            auto m = std::dynamic_pointer_cast<lodestone::obs::CObservationMagnetometer>(o);
            ASSERT_TRUE(m) << "not a magnetometer: " << o->GetRuntimeClass()->className;
            got.push_back(m);
        }
    };
    // The first readings are held back until their field is shown to be Earth's.
    auto& driver = dynamic_cast<lodestone::drivers::CMagnetometerFromImu&>(*s);
    const auto held = lodestone::drivers::CMagnetometerFromImu::kPlausibilityReadings;
    std::size_t calls = 0;
    const auto withField = [&] { return calls - driver.droppedImuWithoutMagnetometer(); };
    while (withField() < held - 1) {
        take();
        ++calls;
    }
    EXPECT_TRUE(got.empty()) << got.size() << " readings out before the unit was checked";
    while (withField() < held + 4) {
        take();
        ++calls;
    }
    ASSERT_EQ(got.size(), held + 4);
    EXPECT_EQ(driver.droppedImuWithoutMagnetometer(), calls / 3);  // every third had no field
    EXPECT_NEAR(got[0]->field.x, 20.0, 1e-9);
    EXPECT_NEAR(got[0]->field.z, -40.0, 1e-9);
    EXPECT_NEAR(got[0]->noiseStd.y, 0.3, 1e-12);
    EXPECT_EQ(got[0]->sensorLabel, "MAG");
}

TEST(CMagnetometerFromImu, AHangingImuIsGivenUpOnNamingItsPort) {
    auto s = wrapper("[MAG]\nimu_driver = CHangingImu\nimu_section = XSENS\nunit = uT\ninit_timeout_s = 0.3\n"
                     "[XSENS]\nportname_LIN = /dev/ttyUSB-missing\n");
    const auto start = std::chrono::steady_clock::now();
    try {
        s->initialize();
        FAIL() << "a hanging IMU started";
    } catch (const std::exception& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("/dev/ttyUSB-missing"), std::string::npos) << what;
        EXPECT_NE(what.find("sensor section 'MAG'"), std::string::npos) << what;
    }
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(waited, 2.0);
    s->doProcess();  // the abandoned driver is not touched
}

TEST(CMagnetometerFromImu, ConfigurationMistakesNameTheKey) {
    const auto refusal = [](const std::string& ini) -> std::string {
        try {
            wrapper(ini);
        } catch (const std::exception& e) {
            return e.what();
        }
        return "(accepted)";
    };
    EXPECT_NE(refusal("[MAG]\nimu_section = IMU\n").find("key 'imu_driver'"), std::string::npos);
    EXPECT_NE(refusal("[MAG]\nimu_driver = CNoSuchImu\nimu_section = IMU\nunit = uT\n").find("CNoSuchImu"),
              std::string::npos);
    EXPECT_NE(refusal("[MAG]\nimu_driver = CFakeImu\nimu_section = IMU\nunit = furlongs\n").find("key 'unit'"),
              std::string::npos);
    // The unit is never assumed: MRPT says gauss, Xsens writes normalized units.
    const auto missing = refusal("[MAG]\nimu_driver = CFakeImu\nimu_section = IMU\n");
    EXPECT_NE(missing.find("key 'unit': missing"), std::string::npos) << missing;
}

TEST(CMagnetometerFromImu, AFieldThatIsNotEarthsInTheGivenUnitFailsNamingTheKeyAndRecordsNothing) {
    // The fake reports 0.45 gauss; read as microtesla (or as normalized units of a 50 uT field:
    // 22 uT, plausible) - uT is 100 times off.
    auto s = wrapper("[MAG]\nsensorLabel = MAG\nimu_driver = CFakeImu\nimu_section = IMU\nunit = uT\n[IMU]\n");
    s->initialize();
    std::size_t out = 0;
    std::string error;
    for (int i = 0; i < 100 && error.empty(); ++i) {
        try {
            s->doProcess();
        } catch (const std::exception& e) {
            error = e.what();
        }
        out += s->getObservations().size();
    }
    EXPECT_EQ(out, 0u) << "readings in a wrong unit were recorded";
    EXPECT_NE(error.find("sensor section 'MAG', key 'unit' = uT"), std::string::npos) << error;
    EXPECT_NE(error.find("0.4472 uT"), std::string::npos) << error;
    EXPECT_NE(error.find("as gauss they would be plausible"), std::string::npos) << error;
}
