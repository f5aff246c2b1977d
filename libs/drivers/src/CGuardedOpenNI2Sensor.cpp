#include <lodestone/drivers/CGuardedOpenNI2Sensor.h>
#include <mrpt/hwdrivers/COpenNI2Sensor.h>

#include "Abandoned.h"

#include <stdexcept>

IMPLEMENTS_GENERIC_SENSOR(CGuardedOpenNI2Sensor, lodestone::drivers)

namespace lodestone::drivers {

CGuardedOpenNI2Sensor::CGuardedOpenNI2Sensor() : camera_(new mrpt::hwdrivers::COpenNI2Sensor) {}

CGuardedOpenNI2Sensor::~CGuardedOpenNI2Sensor() {
    // Without a device COpenNI2Sensor's destructor throws (std::terminate): leave it be.
    if (found_device_) {
        delete camera_;
    } else {
        detail::abandon(camera_);
    }
}

void CGuardedOpenNI2Sensor::loadConfig_sensorSpecific(const mrpt::config::CConfigFileBase& config,
                                                      const std::string& section) {
    section_ = section;
    camera_->loadConfig(config, section);
}

void CGuardedOpenNI2Sensor::setPathForExternalImages(const std::string& directory) {
    camera_->setPathForExternalImages(directory);
}

void CGuardedOpenNI2Sensor::initialize() {
    camera_->initialize();
    if (camera_->getNumDevices() <= 0) {
        throw std::runtime_error("sensor section '" + section_ +
                                 "': no OpenNI2 device found (COpenNI2Sensor) - is the camera "
                                 "plugged in and powered?");
    }
    found_device_ = true;
    m_state = ssWorking;
}

void CGuardedOpenNI2Sensor::doProcess() {
    if (!found_device_) return;  // COpenNI2Sensor asserts (aborts) without a device
    camera_->doProcess();
    for (auto& [t, o] : camera_->getObservations()) appendObservation(o);
}

}  // namespace lodestone::drivers
