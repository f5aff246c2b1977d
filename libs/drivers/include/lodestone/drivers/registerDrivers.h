#pragma once

namespace lodestone::drivers {

/** Registers Lodestone's CGenericSensor drivers in MRPT's sensor factory, so
 * CGenericSensor::createSensor("CSimulatedRobot") (and rawlog-grabber's `driver =`) finds
 * them. Idempotent. */
void registerDrivers();

}  // namespace lodestone::drivers
