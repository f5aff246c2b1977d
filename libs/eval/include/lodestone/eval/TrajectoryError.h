#pragma once

#include <lodestone/io/TumTrajectory.h>

#include <Eigen/Geometry>
#include <utility>
#include <vector>

namespace lodestone::eval {

/** Pairs (estimate index, ground-truth index) whose timestamps differ by at most `maxDt` [s],
 * each ground-truth pose used once, as the TUM RGB-D tools associate. */
std::vector<std::pair<std::size_t, std::size_t>> associate(const std::vector<io::TumPose>& est,
                                                           const std::vector<io::TumPose>& gt,
                                                           double maxDt = 0.02);

/** The ground-truth pose nearest `t` (`truth` sorted by time), if one lies within `maxDt`;
 * else nullptr. */
const io::TumPose* truthAt(const std::vector<io::TumPose>& truth, double t, double maxDt);

/** Absolute trajectory error (TUM RGB-D benchmark): the estimate rigidly aligned to the ground
 * truth (Horn's method: least squares over the associated positions, no scale), then the
 * translational differences. */
struct AteResult {
    std::size_t pairs{0};
    double rmse{0}, mean{0}, median{0}, max{0};                  ///< [m]
    Eigen::Isometry3d alignment{Eigen::Isometry3d::Identity()};  ///< applied to the estimate
    std::vector<double> errors;  ///< per associated pair [m], estimate order
    std::vector<double> times;   ///< their timestamps [s]
};
AteResult absoluteTrajectoryError(const std::vector<io::TumPose>& est,
                                  const std::vector<io::TumPose>& gt, double maxDt = 0.02);

/** Relative pose error (TUM RGB-D benchmark): for pose pairs a fixed interval apart, the
 * difference between estimated and true relative motion. Intervals in seconds ("per second")
 * or in travelled ground-truth distance ("per metre"). */
struct RpeResult {
    std::size_t pairs{0};
    double translationRmse{0};  ///< [m] per interval
    double rotationRmse{0};     ///< [rad] per interval
};
enum class RpeInterval { Seconds, Metres };
RpeResult relativePoseError(const std::vector<io::TumPose>& est, const std::vector<io::TumPose>& gt,
                            RpeInterval kind, double interval, double maxDt = 0.02);

}  // namespace lodestone::eval
