#pragma once

#include <lodestone/datasets/PinholeIntrinsics.h>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <string>

namespace lodestone::datasets {

/** Depth from its own camera into the colour camera's pixels, for datasets whose depth images
 * are not registered to colour (a Kinect's raw depth, ETH3D's, a calibrated rig's): the depth
 * camera's intrinsics and its pose in the colour camera's optical frame. */
struct DepthRegistration {
    PinholeIntrinsics depth;
    /** p_colour = colourFromDepth * p_depth [m]. */
    Eigen::Isometry3d colourFromDepth{Eigen::Isometry3d::Identity()};

    /** "tx,ty,tz,qx,qy,qz,qw": the depth camera's pose in the colour camera's optical frame
     * (metres, a unit quaternion - it is normalized; a zero one is an error). Throws
     * std::invalid_argument naming the text. */
    static Eigen::Isometry3d parsePose(const std::string& text);
};

/** Each depth pixel back-projected through the depth camera, moved into the colour camera and
 * projected onto a colour-sized image (`colourSize`); where several land on one pixel the
 * nearest wins (what is in front hides what is behind, as the colour camera sees it). Raw
 * 16-bit values in and out, same units (`depthScale` per metre); values from `invalidFrom` up
 * and 0 mean "no depth", as do colour pixels nothing lands on. Forward splatting to the
 * nearest pixel: where colour has a finer grid than depth, single-pixel holes stay holes. */
cv::Mat registerDepthToColour(const cv::Mat& depth16, const DepthRegistration& registration,
                              const PinholeIntrinsics& colour, cv::Size colourSize,
                              double depthScale, unsigned invalidFrom = 65535);

}  // namespace lodestone::datasets
