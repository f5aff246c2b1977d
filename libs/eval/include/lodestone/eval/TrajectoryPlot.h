#pragma once

#include <lodestone/eval/TrajectoryError.h>

#include <opencv2/core.hpp>

namespace lodestone::eval {

/** A picture of an evaluation: left, the ground truth (black) and the aligned estimate (red)
 * seen from above with equal axes; right, the absolute error over time. */
cv::Mat3b plotTrajectories(const std::vector<io::TumPose>& est, const std::vector<io::TumPose>& gt,
                           const AteResult& ate);

}  // namespace lodestone::eval
