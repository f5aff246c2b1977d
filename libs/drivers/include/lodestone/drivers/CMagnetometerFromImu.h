#pragma once

#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/obs/MagneticUnit.h>
#include <mrpt/hwdrivers/CGenericSensor.h>
#include <mrpt/math/TPoint3D.h>

#include <string>
#include <vector>

namespace lodestone::drivers {

/** A magnetometer read through any MRPT IMU driver (CIMUXSens_MT4, or another class by name):
 * the inner driver runs as configured in its own INI section, and every CObservationIMU it
 * emits with IMU_MAG_X/Y/Z becomes a lodestone::obs::CObservationMagnetometer in microtesla
 * (obs::magnetometerFromImu with the `unit` given: Xsens fills those channels in its normalized
 * units, "xsens:<local field uT>", not the gauss MRPT documents). IMU observations without the
 * magnetometer channels are dropped.
 *
 * The inner driver's initialize() runs on a thread of its own and is given `init_timeout_s`:
 * CIMUXSens_MT4 on a port that does not exist was seen to hang for over a minute. Past the
 * timeout the error names the port, and the hung driver is abandoned (never destroyed: its
 * destructor is where it hangs).
 *
 * The unit is never assumed: the first kPlausibilityReadings readings are held back and their
 * median magnitude checked against Earth's field (obs::implausibleFieldMagnitude); in a wrong
 * unit the sensor fails naming its `unit` key, and nothing it read is recorded.
 *
 * INI keys (the sensor's section): imu_driver (required: a CGenericSensor class), imu_section
 * (required: the section the inner driver reads), unit (required) = gauss | uT | T |
 * normalized:<uT> (xsens:<uT> the same), calibrated = true, noise_std_uT = 0 (per axis),
 * init_timeout_s = 10. */
class CMagnetometerFromImu : public mrpt::hwdrivers::CGenericSensor {
    DEFINE_GENERIC_SENSOR(CMagnetometerFromImu)

  public:
    CMagnetometerFromImu();
    ~CMagnetometerFromImu() override;

    void initialize() override;
    void doProcess() override;
    void setPathForExternalImages(const std::string& directory) override;

    std::size_t droppedImuWithoutMagnetometer() const { return dropped_; }
    /** Readings held back at the start until their field is shown to be Earth's. */
    static constexpr std::size_t kPlausibilityReadings = 20;

  protected:
    void loadConfig_sensorSpecific(const mrpt::config::CConfigFileBase& config,
                                   const std::string& section) override;

  private:
    std::string section_, imu_driver_, imu_section_, port_;
    obs::MagneticUnit unit_;
    bool calibrated_{true};
    double noise_std_{0}, init_timeout_s_{10};
    mrpt::hwdrivers::CGenericSensor* inner_{nullptr};  // owned unless abandoned (see above)
    std::size_t dropped_{0};
    std::vector<obs::CObservationMagnetometer::Ptr> held_;  // the first readings, until checked
};

}  // namespace lodestone::drivers
