#pragma once

#include <mrpt/hwdrivers/CGenericSensor.h>

#include <chrono>
#include <memory>
#include <string>

namespace lodestone::sim {
class SimulatorSource;
}
namespace lodestone::io {
class TumTrajectoryWriter;
}

namespace lodestone::drivers {

/** A lodestone-sim scenario streamed as a live sensor, so the whole live path (rawlog-grabber,
 * lodestone-grab, live SLAM) runs without hardware. Every simulated sensor's observations come
 * out of this one driver, keeping the simulator's labels (WHEELS, RGBD, MAG_LEFT, ...), when
 * their time is due: scenario time runs `time_scale` times as fast as the wall clock.
 *
 * Timestamps: the grab's start (the wall clock at the first doProcess()) plus the scenario time
 * since its start, so data keeps its true spacing at any time_scale.
 *
 * INI keys (the sensor's section):
 *   scenario    = a lodestone-sim scenario INI (required)
 *   time_scale  = 1.0    scenario seconds per wall second (> 0)
 *   camera      = WxH@HZ override the scenario's camera (optional)
 *   seed        = 0      the simulator's seed
 *   max_seconds = inf    stop after this much scenario time
 *   ground_truth = FILE  write the true pose at every observation there (TUM, the grab's
 *                        clock): what lodestone-slam --ground-truth compares a grabbed run with
 * Colour images go to the folder given by setPathForExternalImages() (as MRPT's camera drivers
 * do, PNG) when one is set, else stay inside the observation. */
class CSimulatedRobot : public mrpt::hwdrivers::CGenericSensor {
    DEFINE_GENERIC_SENSOR(CSimulatedRobot)

  public:
    CSimulatedRobot();
    ~CSimulatedRobot() override;

    /** Builds the simulator; throws std::runtime_error naming the section and key on a bad
     * scenario or value. */
    void initialize() override;
    /** Appends every observation whose time is due. */
    void doProcess() override;
    void setPathForExternalImages(const std::string& directory) override;

    /** The scenario ran to its end (or max_seconds). */
    bool finished() const { return finished_; }
    double timeScale() const { return time_scale_; }

  protected:
    void loadConfig_sensorSpecific(const mrpt::config::CConfigFileBase& config,
                                   const std::string& section) override;

  private:
    void emit(const mrpt::obs::CObservation::Ptr& obs);
    void finish();

    std::string section_, scenario_path_, camera_, images_dir_, truth_path_;
    std::unique_ptr<io::TumTrajectoryWriter> truth_;
    double time_scale_{1.0}, max_seconds_{0};
    std::uint64_t seed_{0};
    std::unique_ptr<sim::SimulatorSource> sim_;
    mrpt::obs::CObservation::Ptr pending_;  // fetched, not yet due
    bool started_{false}, finished_{false};
    std::chrono::steady_clock::time_point wall_start_;
    double grab_start_{0};  // wall clock at the first doProcess [s since the epoch]
    double sim_start_{0};   // the scenario's start time [s since the epoch]
    std::size_t images_written_{0};
};

}  // namespace lodestone::drivers
