#pragma once

#include <lodestone/sim/Scenario.h>
#include <lodestone/sim/SimSensor.h>

#include <vector>

namespace lodestone::sim {

/** The base's wheel-drop switches: a CObservationWheelDrop when the robot is lifted (both
 * wheels drop) and when it is put down again. */
class SimWheelDrop : public SimSensor {
  public:
    SimWheelDrop(const MotionPlan& plan, const std::string& label, double startTime);
    std::int64_t nextTimeNs() const override;
    mrpt::obs::CObservation::Ptr produce() override;

  private:
    std::string label_;
    double start_time_;
    std::vector<std::pair<std::int64_t, bool>> events_;  // (time, lifted)
    std::size_t next_{0};
};

}  // namespace lodestone::sim
