#pragma once

#include <lodestone/sim/Random.h>
#include <lodestone/sim/Scenario.h>
#include <lodestone/sim/SimSensor.h>

namespace lodestone::sim {

/** Wheel encoders of a differential-drive base: absolute tick counts with wheel slip noise,
 * systematic scale errors and quantization, plus the base's own dead-reckoned pose (integrated
 * from the ticks, midpoint rule), as CObservationOdometry. Lifted wheels do not turn. */
class SimEncoders : public SimSensor {
  public:
    SimEncoders(const MotionPlan& plan, const EncoderSpec& spec, double startTime, Random rng);
    std::int64_t nextTimeNs() const override;
    mrpt::obs::CObservation::Ptr produce() override;

  private:
    const MotionPlan& plan_;
    EncoderSpec spec_;
    double start_time_;
    Random rng_;
    SampleClock clock_;
    Eigen::Vector2d last_true_{0, 0};  // true wheel angles at the previous sample [rad]
    Eigen::Vector2d measured_{0, 0};   // measured wheel angles [rad]
    Eigen::Vector2i last_ticks_{0, 0};
    double x_{0}, y_{0}, yaw_{0};  // dead reckoning from the ticks
    bool first_{true};
};

}  // namespace lodestone::sim
