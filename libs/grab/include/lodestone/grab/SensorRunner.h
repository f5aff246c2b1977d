#pragma once

#include <lodestone/grab/GrabConfig.h>
#include <mrpt/hwdrivers/CGenericSensor.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace lodestone::grab {

/** What the sensor threads hand the writer: objects in arrival order, from every sensor. */
class ObservationQueue {
  public:
    void push(std::vector<mrpt::serialization::CSerializable::Ptr> objects);
    /** Everything queued so far (waits up to `wait` for something to arrive). */
    std::vector<mrpt::serialization::CSerializable::Ptr> takeAll(std::chrono::milliseconds wait);

  private:
    std::mutex mutex_;
    std::condition_variable arrived_;
    std::vector<mrpt::serialization::CSerializable::Ptr> items_;
};

/** One sensor on a thread of its own: doProcess() at its process_rate, its observations into
 * the queue. A driver that throws is stopped and its message kept; the others go on. */
class SensorRunner {
  public:
    enum class State { Running, Finished, Stopped, Died };

    /** Creates the driver by class name, loads its section, initializes it: throws
     * std::runtime_error naming the section (and the driver) on any failure. */
    SensorRunner(const SensorSection& sensor, const mrpt::config::CConfigFileBase& ini,
                 const std::string& imagesDir, ObservationQueue& queue);
    ~SensorRunner();
    SensorRunner(const SensorRunner&) = delete;
    SensorRunner& operator=(const SensorRunner&) = delete;

    void start();
    /** Asks the thread to stop and joins it (the last observations are queued first). */
    void stop();

    const std::string& section() const { return sensor_.section; }
    State state() const { return state_.load(); }
    std::string error() const;
    std::size_t produced() const { return produced_.load(); }  ///< objects queued so far

  private:
    void run();

    SensorSection sensor_;
    mrpt::hwdrivers::CGenericSensor::Ptr driver_;
    ObservationQueue& queue_;
    std::thread thread_;
    std::atomic<bool> stop_{false};
    std::atomic<State> state_{State::Running};
    std::atomic<std::size_t> produced_{0};
    mutable std::mutex error_mutex_;
    std::string error_;
};

const char* toString(SensorRunner::State s);

}  // namespace lodestone::grab
