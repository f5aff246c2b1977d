#include <lodestone/sim/SimEncoders.h>
#include <lodestone/sim/SimGyro.h>
#include <lodestone/sim/SimMagnetometer.h>
#include <lodestone/sim/SimRgbdCamera.h>
#include <lodestone/sim/SimWheelDrop.h>
#include <lodestone/sim/SimulatorSource.h>

#include <limits>

namespace lodestone::sim {

SimulatorSource::SimulatorSource(const Scenario& scenario, std::uint64_t seed)
    : scenario_(scenario) {
    Random rng(seed);
    const std::uint64_t fromRun = rng.fork(100).nextU64();
    world_ = std::make_unique<World>(
        scenario_, scenario_.worldSeed ? Random(*scenario_.worldSeed).fork(100).nextU64() : fromRun);
    const FloorPlan& plan = world_->floorPlan();
    const double radius = scenario_.robotRadius;
    plan_ = std::make_unique<MotionPlan>(scenario_.motion, scenario_.kidnaps,
                                         [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
                                             return !plan.blocks(a, b, radius);
                                         });
    const double t0 = scenario_.startTime;
    // Sensor order here is the tie-break order of simultaneous samples.
    if (scenario_.handheld) {
        handheld_ = std::make_unique<HandheldMotion>(*plan_, *scenario_.handheld, rng.fork(3));
    }
    if (!scenario_.cameraOnly && !scenario_.handheld) {
        sensors_.push_back(std::make_unique<SimEncoders>(*plan_, scenario_.encoders, t0, rng.fork(1)));
        sensors_.push_back(
            std::make_unique<SimWheelDrop>(*plan_, scenario_.encoders.wheelDropLabel, t0));
        for (std::size_t i = 0; i < scenario_.magnetometers.size(); ++i) {
            sensors_.push_back(std::make_unique<SimMagnetometer>(
                *world_, *plan_, scenario_.magnetometers[i], t0, rng.fork(10 + i)));
        }
    }
    if (scenario_.gyro) {
        // On the robot or in the hand; its own noise stream (fork 4), so adding it leaves every
        // other sensor's samples as they were.
        sensors_.push_back(std::make_unique<SimGyro>(*plan_, handheld_.get(), *scenario_.gyro, t0,
                                                     rng.fork(4)));
    }
    if (scenario_.camera.enabled) {
        sensors_.push_back(
            std::make_unique<SimRgbdCamera>(*world_, *plan_, scenario_.camera, t0, rng.fork(2),
                                            handheld_.get()));
    }
}

SimulatorSource::~SimulatorSource() = default;

mrpt::obs::CObservation::Ptr SimulatorSource::next() {
    SimSensor* earliest = nullptr;
    std::int64_t best = std::numeric_limits<std::int64_t>::max();
    for (auto& s : sensors_) {
        const std::int64_t t = s->nextTimeNs();
        if (t < best) {
            best = t;
            earliest = s.get();
        }
    }
    if (!earliest) return nullptr;
    last_time_ns_ = best;
    return earliest->produce();
}

mrpt::poses::CPose3D SimulatorSource::truePose3D(double t) const {
    if (handheld_) {
        mrpt::math::CMatrixDouble44 M(handheld_->poseAt(t).matrix());
        return mrpt::poses::CPose3D(M);
    }
    const RobotPose p = plan_->poseAt(t);
    return {p.x, p.y, p.z, p.yaw, 0, 0};
}

std::vector<KidnapEvent> SimulatorSource::kidnapEvents() const {
    std::vector<KidnapEvent> events;
    for (const auto& s : plan_->segments()) {
        if (s.kind == MotionSegment::Kind::Carry) {
            events.push_back({scenario_.startTime + s.t0, scenario_.startTime + s.t1, s.end});
        }
    }
    return events;
}

std::vector<io::KidnapEventRecord> kidnapRecords(const SimulatorSource& source) {
    std::vector<io::KidnapEventRecord> out;
    int index = 1;
    for (const auto& e : source.kidnapEvents()) {
        out.push_back({index++, e.start, e.end, e.putDown.x, e.putDown.y, e.putDown.yaw});
    }
    return out;
}

}  // namespace lodestone::sim
