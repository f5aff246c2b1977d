#pragma once

#include <lodestone/sim/SimulatorSource.h>

#include <opencv2/core.hpp>

namespace lodestone::sim {

/** A top view of a scenario, drawn with libs/plot (metres on both axes, equal aspect; the map
 * at least 640 px across, more where `pixelsPerMetre` asks): the field magnitude |B| [uT] at the
 * magnetometers' height as a colour map with its scale, walls (thick black: textured, thin
 * grey: plain), the robot's path, the start and every kidnap (carried, put down). */
cv::Mat3b plotScenario(const SimulatorSource& source, double pixelsPerMetre = 40);

}  // namespace lodestone::sim
