#pragma once

#include <mrpt/img/TColor.h>

#include <string>

namespace lodestone::view {

/** The view's colours, one place: each keyframe segment its own (the 2D plots' series
 * colours), each loop closer its own (the same closer the same colour in every picture). */
mrpt::img::TColor segmentColour(int segment);
mrpt::img::TColor closerColour(const std::string& closer);
mrpt::img::TColor odometryColour();
mrpt::img::TColor refusedColour();
mrpt::img::TColor truthColour();

}  // namespace lodestone::view
