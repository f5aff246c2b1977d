#pragma once

#include <lodestone/graphslam/AttitudePrior.h>
#include <lodestone/graphslam/PoseGraph.h>
#include <lodestone/vision/depth/LevelSurfaces.h>

#include <Eigen/Geometry>
#include <cstddef>
#include <functional>
#include <optional>

namespace lodestone::graphslam {

/** The floor as a landmark the nodes see: where a node's depth holds level surfaces
 * (vision::fitLevelSurfaces - the floor, a ceiling, a table top), their common up is the node's
 * up, measured, and its height above the floor a measurement of its height along the map's up:
 * an AttitudePrior with `height` (the graph's floor is AttitudePriors::mapHeight). A building's
 * floor is level - to tenths of a degree, far better than a carrier holds its camera - so
 * nothing is assumed of the carrier, only of the floor: not for stairs or ramps.
 *
 * Which surface is the floor, and whether a surface is level at all, is decided against the
 * floor seen last: the up it gave, carried to this node by the nodes' poses in the graph,
 * within `upGate` (VO's tilt over a gap's turn: degrees; a ramp's slope beyond it is not
 * taken); the floor the surface nearest its height carried the same way, within `heightGate`
 * (a table top is 0.7 m above it). The first floor: the lowest surface, its up within `upGate`
 * of the robot frame's z (a carrier that starts with its camera about level). */
class LevelFloor {
  public:
    struct Params {
        vision::LevelSurfaceParams fit;
        double upGate{10 * 3.14159265358979 / 180};  ///< [rad]
        double heightGate{0.3};                      ///< [m]
    };
    LevelFloor();
    explicit LevelFloor(Params params);
    const Params& params() const { return params_; }

    /** The node's up and height above the floor, from its frame's depth `cloud` (optical
     * frame), the camera at `T_robot_optical` on the robot; `poseOf` gives a node's pose in the
     * graph as it is now (this node's included). Nothing where no level surface agrees with
     * the floor seen last. */
    std::optional<AttitudePrior> observe(TNodeID node, const vision::DepthCloud& cloud,
                                         const Eigen::Isometry3d& T_robot_optical,
                                         const std::function<Eigen::Isometry3d(TNodeID)>& poseOf);

    std::size_t ups() const { return ups_; }            ///< nodes given an up
    std::size_t heights() const { return heights_; }    ///< ... of them a height above the floor
    std::size_t rejected() const { return rejected_; }  ///< level surfaces beyond upGate

  private:
    struct Seen {
        TNodeID node;
        Eigen::Vector3d up;            // in the node's robot frame
        std::optional<double> height;  // of the robot's origin above the floor [m]
    };
    Params params_;
    std::optional<Seen> last_;       // the last node that saw a level surface
    std::optional<Seen> lastFloor_;  // ... and the floor
    std::size_t ups_{0}, heights_{0}, rejected_{0};
};

/** Two measurements of one node's up fused (each unit, with its sigma per axis): their
 * information-weighted mean; nothing where they disagree beyond chi-square 99.9 % (2 dof). */
std::optional<AttitudePrior> fuseUps(const AttitudePrior& a, const AttitudePrior& b);

}  // namespace lodestone::graphslam
