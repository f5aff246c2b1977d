#include <lodestone/drivers/CSimulatedRobot.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/sim/Scenario.h>
#include <lodestone/sim/SimulatorSource.h>
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/system/datetime.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "SectionKey.h"

IMPLEMENTS_GENERIC_SENSOR(CSimulatedRobot, lodestone::drivers)

namespace lodestone::drivers {

namespace fs = std::filesystem;

CSimulatedRobot::CSimulatedRobot() = default;
CSimulatedRobot::~CSimulatedRobot() = default;

void CSimulatedRobot::loadConfig_sensorSpecific(const mrpt::config::CConfigFileBase& config,
                                                const std::string& section) {
    section_ = section;
    const auto where = [&](const char* key) { return detail::sectionKey(section, key); };
    scenario_path_ = config.read_string(section, "scenario", "");
    if (scenario_path_.empty()) throw std::runtime_error(where("scenario") + ": missing (a lodestone-sim scenario INI)");
    time_scale_ = config.read_double(section, "time_scale", 1.0);
    if (!(time_scale_ > 0) || !std::isfinite(time_scale_)) {
        throw std::runtime_error(where("time_scale") + ": must be a number > 0");
    }
    max_seconds_ = config.read_double(section, "max_seconds", std::numeric_limits<double>::infinity());
    if (!(max_seconds_ > 0)) throw std::runtime_error(where("max_seconds") + ": must be > 0");
    const int seed = config.read_int(section, "seed", 0);
    if (seed < 0) throw std::runtime_error(where("seed") + ": must be >= 0");
    seed_ = static_cast<std::uint64_t>(seed);
    camera_ = config.read_string(section, "camera", "");
    truth_path_ = config.read_string(section, "ground_truth", "");
}

void CSimulatedRobot::initialize() {
    const auto where = [&](const char* key) { return detail::sectionKey(section_, key); };
    sim::Scenario scenario;
    try {
        scenario = sim::Scenario::load(scenario_path_);
    } catch (const std::exception& e) {
        throw std::runtime_error(where("scenario") + ": " + e.what());
    }
    if (!camera_.empty() && !scenario.camera.override(camera_)) {
        throw std::runtime_error(where("camera") + ": expected WIDTHxHEIGHT@RATE, got '" + camera_ + "'");
    }
    sim_ = std::make_unique<sim::SimulatorSource>(scenario, seed_);
    if (!truth_path_.empty()) {
        try {
            truth_ = std::make_unique<io::TumTrajectoryWriter>(truth_path_);
        } catch (const std::exception& e) {
            throw std::runtime_error(where("ground_truth") + ": " + e.what());
        }
    }
    sim_start_ = sim_->startTime();
    m_state = ssWorking;
}

void CSimulatedRobot::setPathForExternalImages(const std::string& directory) {
    images_dir_ = directory;
}

void CSimulatedRobot::emit(const mrpt::obs::CObservation::Ptr& obs) {
    // The scenario's time moved onto the grab's clock.
    const double scenarioTime = mrpt::Clock::toDouble(obs->timestamp) - sim_start_;
    const double t = scenarioTime + grab_start_;
    obs->timestamp = mrpt::Clock::fromDouble(t);
    if (truth_) truth_->write(t, sim_->truePose3D(scenarioTime));
    if (!images_dir_.empty()) {
        if (auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs);
            scan && scan->hasIntensityImage && !scan->intensityImage.isExternallyStored()) {
            char name[96];
            std::snprintf(name, sizeof name, "%s_%08zu.png", obs->sensorLabel.c_str(), images_written_++);
            fs::create_directories(images_dir_);
            const std::string path = (fs::path(images_dir_) / name).string();
            if (!scan->intensityImage.saveToFile(path)) {
                throw std::runtime_error("sensor section '" + section_ + "': cannot write " + path);
            }
            scan->intensityImage.setExternalStorage(name);
        }
    }
    appendObservation(obs);
}

void CSimulatedRobot::finish() {
    finished_ = true;
    if (truth_) truth_->close();  // the whole truth of what was emitted
    truth_.reset();
}

void CSimulatedRobot::doProcess() {
    if (!sim_ || finished_) return;
    const auto now = std::chrono::steady_clock::now();
    if (!started_) {
        started_ = true;
        wall_start_ = now;
        grab_start_ = mrpt::Clock::toDouble(mrpt::Clock::now());
    }
    const double due = std::chrono::duration<double>(now - wall_start_).count() * time_scale_;
    while (true) {
        if (!pending_) pending_ = sim_->next();
        if (!pending_) {
            finish();
            return;
        }
        const double t = mrpt::Clock::toDouble(pending_->timestamp) - sim_start_;
        if (t > max_seconds_) {
            finish();
            pending_.reset();
            return;
        }
        if (t > due) return;
        emit(pending_);
        pending_.reset();
    }
}

}  // namespace lodestone::drivers
