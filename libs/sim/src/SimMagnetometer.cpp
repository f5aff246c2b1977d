#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/sim/SimMagnetometer.h>

namespace lodestone::sim {

SimMagnetometer::SimMagnetometer(const World& world, const MotionPlan& plan,
                                 const MagnetometerSpec& spec, double startTime, Random rng)
    : world_(world),
      plan_(plan),
      spec_(spec),
      start_time_(startTime),
      rng_(rng),
      clock_(spec.rate) {}

std::int64_t SimMagnetometer::nextTimeNs() const { return clock_.nextWithin(plan_.duration()); }

mrpt::obs::CObservation::Ptr SimMagnetometer::produce() {
    const std::int64_t tNs = clock_.now();
    ++clock_.k;
    const auto& m = spec_.pose;
    const SensorWorldPose s = sensorInWorld(plan_.poseAt(tNs * 1e-9), m.x, m.y, m.z, m.yaw);
    const Eigen::Vector3d bWorld = world_.field().at(s.position);
    // World -> sensor frame: the sensor is level, rotated by its yaw.
    const double c = std::cos(s.yaw), sn = std::sin(s.yaw);
    const Eigen::Vector3d bSensor(c * bWorld.x() + sn * bWorld.y(),
                                  -sn * bWorld.x() + c * bWorld.y(), bWorld.z());
    auto obs = lodestone::obs::CObservationMagnetometer::Create();
    obs->timestamp = simTimestamp(start_time_, tNs);
    obs->sensorLabel = spec_.label;
    obs->sensorPose = mrpt::poses::CPose3D(m.x, m.y, m.z, m.yaw, 0, 0);
    const Eigen::Vector3d noisy =
        bSensor + spec_.bias +
        spec_.noiseStd * Eigen::Vector3d(rng_.normal(), rng_.normal(), rng_.normal());
    obs->field = {noisy.x(), noisy.y(), noisy.z()};
    obs->noiseStd = {spec_.noiseStd, spec_.noiseStd, spec_.noiseStd};
    obs->calibrated = true;
    return obs;
}

}  // namespace lodestone::sim
