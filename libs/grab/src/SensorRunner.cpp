#include <lodestone/drivers/CSimulatedRobot.h>
#include <lodestone/grab/SensorRunner.h>
#include <lodestone/io/MrptErrorText.h>

#include <chrono>

namespace lodestone::grab {

using Clock = std::chrono::steady_clock;

void ObservationQueue::push(std::vector<mrpt::serialization::CSerializable::Ptr> objects) {
    if (objects.empty()) return;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        for (auto& o : objects) items_.push_back(std::move(o));
    }
    arrived_.notify_one();
}

std::vector<mrpt::serialization::CSerializable::Ptr> ObservationQueue::takeAll(
    std::chrono::milliseconds wait) {
    std::unique_lock<std::mutex> lock(mutex_);
    arrived_.wait_for(lock, wait, [&] { return !items_.empty(); });
    std::vector<mrpt::serialization::CSerializable::Ptr> out;
    out.swap(items_);
    return out;
}

const char* toString(SensorRunner::State s) {
    switch (s) {
        case SensorRunner::State::Running: return "running";
        case SensorRunner::State::Finished: return "finished";
        case SensorRunner::State::Stopped: return "stopped";
        case SensorRunner::State::Died: return "died";
    }
    return "?";
}

SensorRunner::SensorRunner(const SensorSection& sensor, const mrpt::config::CConfigFileBase& ini,
                           const std::string& imagesDir, ObservationQueue& queue)
    : sensor_(sensor), queue_(queue) {
    const std::string who = "sensor section '" + sensor.section + "' (driver " + sensor.driver + ")";
    // MRPT's COpenNI2Sensor ends the process when no camera is attached (an assert in
    // doProcess, a throwing destructor): run it through its guard, with the same INI keys.
    const std::string driver =
        sensor.driver == "COpenNI2Sensor" ? "CGuardedOpenNI2Sensor" : sensor.driver;
    driver_ = mrpt::hwdrivers::CGenericSensor::createSensorPtr(driver);
    if (!driver_) {
        throw std::runtime_error("sensor section '" + sensor.section + "': unknown driver '" +
                                 sensor.driver +
                                 "' (not a CGenericSensor MRPT or Lodestone registers; a plugin "
                                 "of your own: --plugin LIB)");
    }
    try {
        driver_->loadConfig(ini, sensor.section);
        driver_->setPathForExternalImages(imagesDir);
        driver_->initialize();
    } catch (const std::exception& e) {
        const std::string why = io::condensedMrptError(e.what());
        // Our drivers name their section already.
        const bool named = why.rfind("sensor section '" + sensor.section + "'", 0) == 0;
        throw std::runtime_error(named ? why : who + ": " + why);
    }
}

SensorRunner::~SensorRunner() { stop(); }

void SensorRunner::start() { thread_ = std::thread([this] { run(); }); }

void SensorRunner::stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
}

std::string SensorRunner::error() const {
    std::lock_guard<std::mutex> lock(error_mutex_);
    return error_;
}

void SensorRunner::run() {
    const auto period = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(1.0 / sensor_.processRate));
    auto next = Clock::now();
    const auto* simulated = dynamic_cast<const drivers::CSimulatedRobot*>(driver_.get());
    const auto drain = [&] {
        std::vector<mrpt::serialization::CSerializable::Ptr> objects;
        for (auto& [t, o] : driver_->getObservations()) objects.push_back(std::move(o));
        produced_ += objects.size();
        queue_.push(std::move(objects));
    };
    try {
        while (!stop_) {
            driver_->doProcess();
            drain();
            if (simulated && simulated->finished()) {
                state_ = State::Finished;
                return;
            }
            next += period;
            const auto now = Clock::now();
            if (next < now) next = now;  // a slow doProcess: no burst to catch up
            std::this_thread::sleep_until(next);
        }
        drain();
        state_ = State::Stopped;
    } catch (const std::exception& e) {
        {
            std::lock_guard<std::mutex> lock(error_mutex_);
            error_ = io::condensedMrptError(e.what());
        }
        state_ = State::Died;
    }
}

}  // namespace lodestone::grab
