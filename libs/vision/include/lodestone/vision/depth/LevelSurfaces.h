#pragma once

#include <lodestone/vision/depth/DepthCloud.h>

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

namespace lodestone::vision {

/** How level surfaces (a floor, a ceiling, a table top) are found in a depth cloud. */
struct LevelSurfaceParams {
    /** A point is a candidate where its normal lies within this of the expected up (or down):
     * the normals, averaged over a grid cell, still tilt by degrees at a grazing floor [rad]. */
    double normalGate{30 * 3.14159265358979 / 180};
    /** Candidates whose heights along the up differ by more than this start a new surface [m]
     * (a table top and the floor: 0.7 m; a floor's points: the depth noise, centimetres). */
    double separation{0.10};
    std::size_t minPoints{60};  ///< a surface of fewer points is not taken
    /** A surface closer than this to the camera's own height is not taken (a wall's grazing
     * band, a shelf at eye level say nothing of the up) [m]. */
    double minHeight{0.2};
    /** The up is taken only where the surfaces pin it to this per axis (1 sigma) [rad] ... */
    double maxUpSigma{2 * 3.14159265358979 / 180};
    /** ... and never claimed better than this [rad], nor a height than `minHeightSigma` [m]:
     * a real depth camera's calibration tilts a plane by tenths of a degree, and a building's
     * floor is level to about as much - errors every frame of one place shares, which no
     * number of points averages out. */
    double minUpSigma{0.3 * 3.14159265358979 / 180};
    double minHeightSigma{0.01};
    /** A surface's own roughness beside the depth noise [m] (a floor's tiles, a carpet). */
    double roughness{0.002};
};

/** One level surface: the camera's height above it along the up [m] (negative: a ceiling,
 * above the camera), with its sigma, from this many points. */
struct LevelSurface {
    double height{0};
    double sigma{0};
    std::size_t points{0};
};

/** The up the level surfaces in view share (the optical frame's, unit; with its sigma per
 * axis, the larger of the two tilts') and the surfaces, most points first. */
struct LevelSurfaces {
    Eigen::Vector3d up{0, -1, 0};
    double upSigma{0};
    std::vector<LevelSurface> surfaces;
};

/** The level surfaces in `cloud` (optical frame), for a camera whose up is about `expectedUp`
 * (optical frame, unit; within `normalGate`): the points whose normals face up or down, split
 * into surfaces by their height, then one weighted least-squares fit of a common up and each
 * surface's height (Gauss-Newton, the points re-gated at 3 sigma), each point weighted by its
 * depth noise along the up. Its covariance is the fit's, scaled by the residuals where they
 * exceed the noise. Nothing where no surface has enough points or they do not pin the up. */
std::optional<LevelSurfaces> fitLevelSurfaces(const DepthCloud& cloud,
                                              const Eigen::Vector3d& expectedUp,
                                              const LevelSurfaceParams& params = {});

}  // namespace lodestone::vision
