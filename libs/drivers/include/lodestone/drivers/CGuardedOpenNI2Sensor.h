#pragma once

#include <mrpt/hwdrivers/CGenericSensor.h>

#include <string>

namespace mrpt::hwdrivers {
class COpenNI2Sensor;
}

namespace lodestone::drivers {

/** MRPT's COpenNI2Sensor, used as MRPT has it (same INI keys: width, height, fps,
 * device_number, grab_image, grab_depth, pose_*), kept from its two ways of ending the process
 * when no camera is attached: its doProcess() asserts there is a device (abort), and its
 * destructor throws "No OpenNI2 devices found" (terminate). Here initialize() checks for a
 * device and, with none, throws an error naming the section; a sensor that never found its
 * camera is abandoned, not destroyed. lodestone-grab runs `driver = COpenNI2Sensor` through
 * this class. */
class CGuardedOpenNI2Sensor : public mrpt::hwdrivers::CGenericSensor {
    DEFINE_GENERIC_SENSOR(CGuardedOpenNI2Sensor)

  public:
    CGuardedOpenNI2Sensor();
    ~CGuardedOpenNI2Sensor() override;

    void initialize() override;
    void doProcess() override;
    void setPathForExternalImages(const std::string& directory) override;

  protected:
    void loadConfig_sensorSpecific(const mrpt::config::CConfigFileBase& config,
                                   const std::string& section) override;

  private:
    std::string section_;
    mrpt::hwdrivers::COpenNI2Sensor* camera_{nullptr};
    bool found_device_{false};
};

}  // namespace lodestone::drivers
