#include <lodestone/drivers/CSimulatedRobot.h>
#include <lodestone/drivers/registerDrivers.h>

namespace lodestone::drivers {

void registerDrivers() { CSimulatedRobot::doRegister(); }

}  // namespace lodestone::drivers
