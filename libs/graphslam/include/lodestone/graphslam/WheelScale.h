#pragma once

#include <lodestone/graphslam/PoseGraph.h>

#include <Eigen/Core>
#include <map>
#include <utility>

namespace lodestone::graphslam {

/** The wheels' scale errors of a run, estimated with the graph (simultaneous calibration, as
 * Kümmerle et al. 2011 do for a robot's odometry parameters): a wheel whose radius is off by
 * a fraction of a percent turns every straight into an arc, the same arc on every lap, which
 * per-edge noise cannot describe - modelled as noise, it must be so loose that the odometry no
 * longer holds a plain corridor's shape. Each odometry edge carries how its measured motion
 * moves with the two scales; the solve corrects the edge by them, and closures around loops
 * measure them. */
struct WheelScale {
    /** Per odometry edge (from, to): d(x, y, yaw)/d(left scale, right scale). */
    std::map<std::pair<TNodeID, TNodeID>, Eigen::Matrix<double, 3, 2>> edges;
    /** The estimate (fractions: a wheel's true travel is its measured travel times 1 + e). */
    Eigen::Vector2d scale{0, 0};
    /** Prior sigma of each scale [fraction]; 0: not estimated. */
    double sigma{0};

    bool active() const { return sigma > 0 && !edges.empty(); }
};

}  // namespace lodestone::graphslam
