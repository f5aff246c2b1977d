#include <lodestone/graphslam/nrd/LevelFloor.h>

#include <algorithm>
#include <cmath>

namespace lodestone::graphslam {

LevelFloor::LevelFloor() : LevelFloor(Params{}) {}
LevelFloor::LevelFloor(Params params) : params_(params) {}

std::optional<AttitudePrior> LevelFloor::observe(
    TNodeID node, const vision::DepthCloud& cloud, const Eigen::Isometry3d& T_robot_optical,
    const std::function<Eigen::Isometry3d(TNodeID)>& poseOf) {
    const Eigen::Isometry3d T_map_node = poseOf(node);
    const Eigen::Matrix3d& R_ro = T_robot_optical.linear();
    // The up expected here: the last level surface's, carried by the graph's poses (VO's tilt
    // since then); at first the robot frame's z.
    Eigen::Vector3d expected = Eigen::Vector3d::UnitZ();
    if (last_)
        expected = T_map_node.linear().transpose() * (poseOf(last_->node).linear() * last_->up);
    const auto fit = vision::fitLevelSurfaces(cloud, R_ro.transpose() * expected, params_.fit);
    if (!fit) return std::nullopt;
    const Eigen::Vector3d up = (R_ro * fit->up).normalized();
    if (std::acos(std::clamp(up.dot(expected.normalized()), -1.0, 1.0)) > params_.upGate) {
        ++rejected_;  // (a ramp, a wall taken for a floor, or the carrier's start far from level)
        return std::nullopt;
    }
    AttitudePrior prior{up, fit->upSigma};
    ++ups_;
    // Heights of the robot's origin above each surface below the camera: the camera's, less
    // the camera's own height on the robot along the up.
    const double cameraOnRobot = up.dot(T_robot_optical.translation());
    std::optional<double> predicted;
    if (lastFloor_) {
        const Eigen::Isometry3d T_map_floor = poseOf(lastFloor_->node);
        const Eigen::Vector3d upMap = T_map_floor.linear() * lastFloor_->up;
        predicted =
            *lastFloor_->height + upMap.dot(T_map_node.translation() - T_map_floor.translation());
    }
    const vision::LevelSurface* floor = nullptr;
    for (const vision::LevelSurface& s : fit->surfaces) {
        if (!(s.height > 0)) continue;  // (a ceiling)
        const double h = s.height - cameraOnRobot;
        if (predicted) {
            if (std::abs(h - *predicted) > params_.heightGate) continue;
            if (!floor ||
                std::abs(h - *predicted) < std::abs(floor->height - cameraOnRobot - *predicted))
                floor = &s;
        } else if (!floor || s.height > floor->height) {
            floor = &s;  // (the first floor: the lowest surface seen)
        }
    }
    Seen seen{node, up, std::nullopt};
    if (floor) {
        prior.height = floor->height - cameraOnRobot;
        prior.heightSigma = floor->sigma;
        seen.height = prior.height;
        lastFloor_ = seen;
        ++heights_;
    }
    last_ = seen;
    return prior;
}

std::optional<AttitudePrior> fuseUps(const AttitudePrior& a, const AttitudePrior& b) {
    AttitudePrior out = b.heightSigma > 0 ? b : a;  // (the height: whichever measured one)
    if (!(a.sigma > 0) || !(b.sigma > 0)) {
        const AttitudePrior& withUp = a.sigma > 0 ? a : b;
        out.up = withUp.up;
        out.sigma = withUp.sigma;
        return out;
    }
    const double wa = 1 / (a.sigma * a.sigma), wb = 1 / (b.sigma * b.sigma);
    constexpr double kChi2TwoDof999 = 13.816;
    if ((a.up - b.up).squaredNorm() > kChi2TwoDof999 * (a.sigma * a.sigma + b.sigma * b.sigma))
        return std::nullopt;
    out.up = (wa * a.up + wb * b.up).normalized();
    out.sigma = 1 / std::sqrt(wa + wb);
    return out;
}

}  // namespace lodestone::graphslam
