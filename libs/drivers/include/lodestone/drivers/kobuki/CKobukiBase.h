#pragma once

#include <lodestone/drivers/kobuki/KobukiProtocol.h>
#include <mrpt/comms/CSerialPort.h>
#include <mrpt/hwdrivers/CGenericSensor.h>

#include <memory>
#include <optional>
#include <string>

namespace lodestone::odometry {
class DiffDriveOdometry;
}

namespace lodestone::drivers {

/** A Kobuki (TurtleBot 2) base on its serial port (KobukiProtocol.h), read only:
 *  - every basic-sensor-data packet -> CObservationOdometry: absolute encoder ticks (the
 *    base's 16-bit counters unwrapped), the pose integrated from them (odometry::
 *    DiffDriveOdometry, paper 003 eq. 1), the wheel velocities;
 *  - a wheel-drop change -> lodestone::obs::CObservationWheelDrop (the kidnap detector's cue);
 *  - a bumper or cliff change -> CObservationComment ("bumper: left; cliff: none").
 * A corrupt or partial packet is skipped and counted (`corruptPackets()`), never a crash.
 *
 * INI keys (the sensor's section): serial_port (required), baud_rate = 115200,
 * read_timeout_ms = 5, and DiffDriveOdometry's wheel_base, wheel_radius, ticks_per_rev. */
class CKobukiBase : public mrpt::hwdrivers::CGenericSensor {
    DEFINE_GENERIC_SENSOR(CKobukiBase)

  public:
    CKobukiBase();
    ~CKobukiBase() override;

    /** Opens the port; throws std::runtime_error naming the section and the port. */
    void initialize() override;
    /** Reads what the port has (up to read_timeout_ms) and emits its observations. */
    void doProcess() override;

    std::size_t packets() const { return finder_.packets(); }
    std::size_t corruptPackets() const { return finder_.corrupt() + malformed_; }

  protected:
    void loadConfig_sensorSpecific(const mrpt::config::CConfigFileBase& config,
                                   const std::string& section) override;

  private:
    void handle(const kobuki::BasicSensorData& data, mrpt::Clock::time_point now);

    std::string section_, port_name_;
    int baud_{115200}, read_timeout_ms_{5};
    mrpt::comms::CSerialPort port_;
    kobuki::PacketFinder finder_;
    std::unique_ptr<odometry::DiffDriveOdometry> odometry_;
    std::optional<kobuki::BasicSensorData> last_;
    std::int32_t left_ticks_{0}, right_ticks_{0};  // unwrapped
    std::size_t malformed_{0};
};

}  // namespace lodestone::drivers
