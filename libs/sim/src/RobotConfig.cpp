#include <lodestone/sim/RobotConfig.h>

namespace lodestone::sim {

config::IniOverlay withScenarioWheels(const mrpt::config::CConfigFileBase& ini,
                                      const Scenario& scenario, const std::string& sourceName) {
    config::IniOverlay overlay(ini, sourceName);
    overlay.set("wheel_odometry", "wheel_base", scenario.motion.wheelBase);
    overlay.set("wheel_odometry", "wheel_radius", scenario.motion.wheelRadius);
    overlay.set("wheel_odometry", "ticks_per_rev", scenario.encoders.ticksPerRev);
    return overlay;
}

}  // namespace lodestone::sim
