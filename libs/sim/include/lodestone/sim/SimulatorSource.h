#pragma once

#include <lodestone/io/DataSource.h>
#include <lodestone/io/KidnapEvents.h>
#include <lodestone/sim/HandheldMotion.h>
#include <lodestone/sim/MotionPlan.h>
#include <mrpt/poses/CPose3D.h>
#include <lodestone/sim/Scenario.h>
#include <lodestone/sim/SimSensor.h>
#include <lodestone/sim/World.h>

#include <memory>
#include <vector>

namespace lodestone::sim {

/** A kidnap as it happened: for the events file and the evaluation. */
struct KidnapEvent {
    double start, end;  ///< lift and put-down times [s since the epoch]
    RobotPose putDown;
};

/** A scenario run as a DataSource: observations of every simulated sensor in time order
 * (ties in sensor order), with the true robot pose at each. Same scenario + seed, same
 * observations, byte for byte. */
class SimulatorSource : public io::DataSource {
  public:
    SimulatorSource(const Scenario& scenario, std::uint64_t seed);
    ~SimulatorSource() override;

    mrpt::obs::CObservation::Ptr next() override;
    std::string name() const override { return "simulator:" + scenario_.name; }

    /** The true robot (base) pose at `t` [s since the scenario start]. */
    RobotPose truePose(double t) const { return plan_->poseAt(t); }
    /** What the ground truth follows at `t`: the robot's pose, or with a hand-held camera the
     * camera's (it is the robot then). */
    mrpt::poses::CPose3D truePose3D(double t) const;
    /** Scenario time of the observation last returned by next() [s]. */
    double lastTime() const { return last_time_ns_ * 1e-9; }
    double startTime() const { return scenario_.startTime; }
    double duration() const { return plan_->duration(); }
    std::vector<KidnapEvent> kidnapEvents() const;

    const Scenario& scenario() const { return scenario_; }
    const World& world() const { return *world_; }
    const MotionPlan& plan() const { return *plan_; }

  private:
    Scenario scenario_;
    std::unique_ptr<World> world_;
    std::unique_ptr<MotionPlan> plan_;
    std::unique_ptr<HandheldMotion> handheld_;  // null unless the camera is hand-held
    std::vector<std::unique_ptr<SimSensor>> sensors_;
    std::int64_t last_time_ns_{0};
};

/** The source's kidnaps as the events file lists them (index from 1). */
std::vector<io::KidnapEventRecord> kidnapRecords(const SimulatorSource& source);

}  // namespace lodestone::sim
