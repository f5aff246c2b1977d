#pragma once

#include <lodestone/eval/TrajectoryError.h>

#include <opencv2/core.hpp>

namespace lodestone::eval {

/** A picture of an evaluation, drawn with libs/plot: left, the ground truth (grey) and the
 * aligned estimate coloured by its absolute error seen from above (metric axes, equal aspect,
 * centred; the colour bar beside); right, the absolute error over time with its axes. */
cv::Mat3b plotTrajectories(const std::vector<io::TumPose>& est, const std::vector<io::TumPose>& gt,
                           const AteResult& ate);

}  // namespace lodestone::eval
