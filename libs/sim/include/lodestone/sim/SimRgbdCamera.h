#pragma once

#include <lodestone/sim/HandheldMotion.h>
#include <lodestone/sim/RgbdRenderer.h>
#include <lodestone/sim/SimSensor.h>

namespace lodestone::sim {

/** The RGB-D camera: rendered frames as CObservation3DRangeScan with MRPT's conventions (depth
 * frame +X forward, +Y left, +Z up; range_is_depth; 1 mm range units; RGB and depth
 * registered, i.e. the same intrinsics). */
class SimRgbdCamera : public SimSensor {
  public:
    /** With `handheld`, the camera is carried by hand: rendered from its 6-DoF pose, and it is
     * the robot (sensorPose identity). */
    SimRgbdCamera(const World& world, const MotionPlan& plan, const CameraSpec& spec,
                  double startTime, Random rng, const HandheldMotion* handheld = nullptr);
    std::int64_t nextTimeNs() const override;
    mrpt::obs::CObservation::Ptr produce() override;

    const RgbdRenderer& renderer() const { return renderer_; }

  private:
    const MotionPlan& plan_;
    const HandheldMotion* handheld_;
    CameraSpec spec_;
    double start_time_;
    Random rng_;
    SampleClock clock_;
    RgbdRenderer renderer_;
};

}  // namespace lodestone::sim
