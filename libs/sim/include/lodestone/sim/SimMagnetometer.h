#pragma once

#include <lodestone/sim/Random.h>
#include <lodestone/sim/Scenario.h>
#include <lodestone/sim/SimSensor.h>
#include <lodestone/sim/World.h>

namespace lodestone::sim {

/** A 3-axis magnetometer on the robot: the world field at the sensor, in the sensor frame,
 * plus a constant bias and white noise, as CObservationMagnetometer [uT]. */
class SimMagnetometer : public SimSensor {
  public:
    SimMagnetometer(const World& world, const MotionPlan& plan, const MagnetometerSpec& spec,
                    double startTime, Random rng);
    std::int64_t nextTimeNs() const override;
    mrpt::obs::CObservation::Ptr produce() override;

  private:
    const World& world_;
    const MotionPlan& plan_;
    MagnetometerSpec spec_;
    double start_time_;
    Random rng_;
    SampleClock clock_;
};

}  // namespace lodestone::sim
