#pragma once

#include <lodestone/sim/SimulatorSource.h>

#include <opencv2/core.hpp>

namespace lodestone::sim {

/** A top view of a scenario: field magnitude |B| [uT] at the magnetometers' height as a colour
 * map (with its scale), walls (thick: textured, thin grey: plain), the robot's path, the start
 * and every kidnap put-down. +y points up in the picture. */
cv::Mat3b plotScenario(const SimulatorSource& source, double pixelsPerMetre = 40);

}  // namespace lodestone::sim
