#include <lodestone/drivers/CMagnetometerFromImu.h>
#include <lodestone/obs/ImuMagnetometerConversion.h>
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/obs/CObservationIMU.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <memory>
#include <stdexcept>
#include <thread>

#include "Abandoned.h"
#include "SectionKey.h"

IMPLEMENTS_GENERIC_SENSOR(CMagnetometerFromImu, lodestone::drivers)

namespace lodestone::drivers {

namespace {
std::string seconds(double s) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", s);
    return buf;
}

// What the inner driver calls its port, for the message when it hangs: the keys MRPT's IMU
// drivers use, else the section name.
std::string portOf(const mrpt::config::CConfigFileBase& c, const std::string& section) {
    for (const char* key : {"portname_LIN", "serial_port", "COM_port_LIN", "port"}) {
        const std::string v = c.read_string(section, key, "");
        if (!v.empty()) return v;
    }
    return "(no port key in [" + section + "])";
}
}  // namespace

CMagnetometerFromImu::CMagnetometerFromImu() = default;

CMagnetometerFromImu::~CMagnetometerFromImu() { delete inner_; }

void CMagnetometerFromImu::loadConfig_sensorSpecific(const mrpt::config::CConfigFileBase& config,
                                                     const std::string& section) {
    section_ = section;
    imu_driver_ = config.read_string(section, "imu_driver", "");
    if (imu_driver_.empty()) throw std::runtime_error(detail::sectionKey(section, "imu_driver") + ": missing (e.g. CIMUXSens_MT4)");
    imu_section_ = config.read_string(section, "imu_section", "");
    if (imu_section_.empty()) throw std::runtime_error(detail::sectionKey(section, "imu_section") + ": missing");
    // No default: MRPT documents these channels in gauss, Xsens fills them in its normalized
    // units, other IMUs in microtesla - a guess is wrong by 50x or 100x for someone.
    const std::string unit = config.read_string(section, "unit", "");
    if (unit.empty()) {
        throw std::runtime_error(detail::sectionKey(section, "unit") +
                                 ": missing - the IMU's magnetometer unit, " +
                                 obs::kMagneticUnitChoices +
                                 " (Xsens: normalized:<the field strength at calibration, uT>)");
    }
    try {
        unit_ = obs::MagneticUnit::parse(unit);
    } catch (const std::exception& e) {
        throw std::runtime_error(detail::sectionKey(section, "unit") + ": " + e.what());
    }
    calibrated_ = config.read_bool(section, "calibrated", true);
    noise_std_ = config.read_double(section, "noise_std_uT", 0.0);
    if (!(noise_std_ >= 0)) throw std::runtime_error(detail::sectionKey(section, "noise_std_uT") + ": must be >= 0");
    init_timeout_s_ = config.read_double(section, "init_timeout_s", 10.0);
    if (!(init_timeout_s_ > 0)) throw std::runtime_error(detail::sectionKey(section, "init_timeout_s") + ": must be > 0");
    port_ = portOf(config, imu_section_);
    inner_ = mrpt::hwdrivers::CGenericSensor::createSensor(imu_driver_);
    if (!inner_) {
        throw std::runtime_error(detail::sectionKey(section, "imu_driver") + ": unknown driver '" + imu_driver_ + "'");
    }
    try {
        inner_->loadConfig(config, imu_section_);
    } catch (const std::exception& e) {
        throw std::runtime_error("sensor section '" + section + "': the IMU's section '" +
                                 imu_section_ + "': " + e.what());
    }
}

void CMagnetometerFromImu::setPathForExternalImages(const std::string& directory) {
    if (inner_) inner_->setPathForExternalImages(directory);
}

void CMagnetometerFromImu::initialize() {
    // On its own thread, bounded: the promise is shared so an abandoned thread can still set it.
    auto done = std::make_shared<std::promise<std::string>>();
    auto result = done->get_future();
    mrpt::hwdrivers::CGenericSensor* inner = inner_;
    std::thread([inner, done] {
        try {
            inner->initialize();
            done->set_value("");
        } catch (const std::exception& e) {
            done->set_value(e.what());
        } catch (...) {
            done->set_value("unknown exception");
        }
    }).detach();
    const auto timeout = std::chrono::duration<double>(init_timeout_s_);
    if (result.wait_for(timeout) != std::future_status::ready) {
        detail::abandon(inner_);  // its thread may still be inside it
        inner_ = nullptr;
        throw std::runtime_error("sensor section '" + section_ + "': the IMU (" + imu_driver_ +
                                 ", section '" + imu_section_ + "') did not start within " +
                                 seconds(init_timeout_s_) + " s on port " + port_ +
                                 " - is it connected?");
    }
    const std::string error = result.get();
    if (!error.empty()) {
        throw std::runtime_error("sensor section '" + section_ + "': the IMU (" + imu_driver_ +
                                 ") on port " + port_ + ": " + error);
    }
    m_state = ssWorking;
}

void CMagnetometerFromImu::doProcess() {
    if (!inner_) return;
    inner_->doProcess();
    for (auto& [t, object] : inner_->getObservations()) {
        const auto* imu = dynamic_cast<const mrpt::obs::CObservationIMU*>(object.get());
        if (!imu || !obs::hasMagnetometerChannels(*imu)) {
            ++dropped_;
            continue;
        }
        auto mag = obs::magnetometerFromImu(*imu, unit_, calibrated_, {noise_std_, noise_std_, noise_std_});
        if (!m_sensorLabel.empty()) mag->sensorLabel = m_sensorLabel;
        if (held_.size() < kPlausibilityReadings) {
            // Held back until the unit is shown right: nothing in a wrong unit is recorded.
            held_.push_back(mag);
            if (held_.size() < kPlausibilityReadings) continue;
            std::vector<double> magnitudes;
            for (const auto& h : held_) magnitudes.push_back(h->magnitude());
            if (const auto why = obs::implausibleFieldMagnitude(std::move(magnitudes))) {
                m_state = ssError;
                throw std::runtime_error(detail::sectionKey(section_, "unit") + " = " +
                                         unit_.name + ": " + *why + "; set the IMU's unit (" +
                                         obs::kMagneticUnitChoices + ")");
            }
            for (auto& h : held_) appendObservation(h);
            continue;
        }
        appendObservation(mag);
    }
}

}  // namespace lodestone::drivers
