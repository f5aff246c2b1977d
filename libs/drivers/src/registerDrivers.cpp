#include <lodestone/drivers/CGuardedOpenNI2Sensor.h>
#include <lodestone/drivers/CMagnetometerFromImu.h>
#include <lodestone/drivers/CSimulatedRobot.h>
#include <lodestone/drivers/kobuki/CKobukiBase.h>
#include <lodestone/drivers/registerDrivers.h>

namespace lodestone::drivers {

void registerDrivers() {
    CSimulatedRobot::doRegister();
    CKobukiBase::doRegister();
    CMagnetometerFromImu::doRegister();
    CGuardedOpenNI2Sensor::doRegister();
}

}  // namespace lodestone::drivers
