#pragma once

#include <lodestone/config/IniOverlay.h>
#include <lodestone/sim/Scenario.h>

#include <string>

namespace lodestone::sim {

/** A SLAM INI with the simulated robot's wheel geometry (the scenario's wheel base, wheel
 * radius and encoder ticks per revolution) in its [wheel_odometry] keys, whatever the INI says:
 * how a run over the simulator configures the odometry through its own parameters. `ini` must
 * outlive the result; errors name it as `sourceName`. */
config::IniOverlay withScenarioWheels(const mrpt::config::CConfigFileBase& ini,
                                      const Scenario& scenario, const std::string& sourceName);

}  // namespace lodestone::sim
