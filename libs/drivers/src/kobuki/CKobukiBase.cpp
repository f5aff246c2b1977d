#include <lodestone/drivers/kobuki/CKobukiBase.h>
#include <lodestone/obs/CObservationWheelDrop.h>
#include <lodestone/odometry/DiffDriveOdometry.h>
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <array>
#include <cmath>
#include <stdexcept>

#include "../SectionKey.h"

IMPLEMENTS_GENERIC_SENSOR(CKobukiBase, lodestone::drivers)

namespace lodestone::drivers {

namespace {
std::string flagsText(std::uint8_t bits, const char* none) {
    std::string s;
    const char* names[] = {"right", "centre", "left"};
    for (int i = 0; i < 3; ++i) {
        if (bits & (1u << i)) s += std::string(s.empty() ? "" : "+") + names[i];
    }
    return s.empty() ? none : s;
}
}  // namespace

CKobukiBase::CKobukiBase() = default;
CKobukiBase::~CKobukiBase() = default;

void CKobukiBase::loadConfig_sensorSpecific(const mrpt::config::CConfigFileBase& config,
                                            const std::string& section) {
    section_ = section;
    port_name_ = config.read_string(section, "serial_port", "");
    if (port_name_.empty()) throw std::runtime_error(detail::sectionKey(section, "serial_port") + ": missing (e.g. /dev/ttyUSB0)");
    baud_ = config.read_int(section, "baud_rate", 115200);
    read_timeout_ms_ = config.read_int(section, "read_timeout_ms", 5);
    if (read_timeout_ms_ < 0 || read_timeout_ms_ > 1000) {
        throw std::runtime_error(detail::sectionKey(section, "read_timeout_ms") + ": must be 0..1000");
    }
    odometry::DiffDriveOdometry::Params p;
    p.wheelBase = config.read_double(section, "wheel_base", p.wheelBase);
    p.wheelRadius = config.read_double(section, "wheel_radius", p.wheelRadius);
    p.ticksPerRev = config.read_double(section, "ticks_per_rev", p.ticksPerRev);
    for (const auto& [key, v] : {std::pair<const char*, double>{"wheel_base", p.wheelBase},
                                 {"wheel_radius", p.wheelRadius}, {"ticks_per_rev", p.ticksPerRev}}) {
        if (!(v > 0) || !std::isfinite(v)) throw std::runtime_error(detail::sectionKey(section, key) + ": must be > 0");
    }
    odometry_ = std::make_unique<odometry::DiffDriveOdometry>(p);
}

void CKobukiBase::initialize() {
    try {
        port_.open(port_name_);
        port_.setConfig(baud_);
        // Reads return what has arrived within the timeout: doProcess never blocks longer.
        port_.setTimeouts(0, 0, read_timeout_ms_, 0, 0);
    } catch (const std::exception& e) {
        throw std::runtime_error("sensor section '" + section_ + "': cannot open serial port '" +
                                 port_name_ + "': " + e.what());
    }
    m_state = ssWorking;
}

void CKobukiBase::doProcess() {
    std::array<std::uint8_t, 512> buf{};
    const std::size_t n = port_.Read(buf.data(), buf.size());
    if (n == 0) return;
    const auto now = mrpt::Clock::now();
    for (const auto& payload : finder_.feed(buf.data(), n)) {
        bool malformed = false;
        const auto data = kobuki::findBasicSensorData(payload, &malformed);
        if (malformed) ++malformed_;
        if (data) handle(*data, now);
    }
}

void CKobukiBase::handle(const kobuki::BasicSensorData& d, mrpt::Clock::time_point now) {
    double dt = 0;
    if (last_) {
        left_ticks_ += kobuki::tickStep(last_->leftEncoder, d.leftEncoder);
        right_ticks_ += kobuki::tickStep(last_->rightEncoder, d.rightEncoder);
        dt = static_cast<std::uint16_t>(d.timestampMs - last_->timestampMs) * 1e-3;
    }
    const auto inc = odometry_->addTicks(left_ticks_, right_ticks_);
    auto odo = mrpt::obs::CObservationOdometry::Create();
    odo->timestamp = now;
    odo->sensorLabel = m_sensorLabel;
    odo->odometry = odometry_->pose().mean;
    odo->hasEncodersInfo = true;
    odo->encoderLeftTicks = left_ticks_;
    odo->encoderRightTicks = right_ticks_;
    if (inc && dt > 0) {
        odo->hasVelocities = true;
        const double v = 0.5 * (inc->leftTravel + inc->rightTravel) / dt;
        const double w = (inc->rightTravel - inc->leftTravel) / odometry_->params().wheelBase / dt;
        odo->velocityLocal = mrpt::math::TTwist2D(v, 0, w);
    }
    appendObservation(odo);

    const bool first = !last_;
    if (first || d.wheelDrop != last_->wheelDrop) {
        auto drop = obs::CObservationWheelDrop::Create();
        drop->timestamp = now;
        drop->sensorLabel = m_sensorLabel + "_WHEEL_DROP";
        drop->rightDropped = (d.wheelDrop & 0x01) != 0;
        drop->leftDropped = (d.wheelDrop & 0x02) != 0;
        appendObservation(drop);
    }
    if (first || d.bumper != last_->bumper || d.cliff != last_->cliff) {
        auto c = mrpt::obs::CObservationComment::Create();
        c->timestamp = now;
        c->sensorLabel = m_sensorLabel + "_CONTACT";
        c->text = "bumper: " + flagsText(d.bumper, "none") + "; cliff: " + flagsText(d.cliff, "none");
        appendObservation(c);
    }
    last_ = d;
}

}  // namespace lodestone::drivers
