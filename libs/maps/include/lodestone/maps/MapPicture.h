#pragma once

#include <lodestone/maps/SavedMap.h>

#include <opencv2/core.hpp>

namespace lodestone::maps {

/** A saved map from above (lodestone-inspect map DIR --plot): |B| of every magnetometer reading
 * placed where its node puts the sensor, averaged per `cell` metres and colour-mapped; each
 * session's path in a colour of its own; keyframes as small circles; metres on both axes at
 * equal aspect. */
cv::Mat3b drawMap(const SavedMap& map, double cell = 0.1);

}  // namespace lodestone::maps
