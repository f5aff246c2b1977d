#pragma once

#include <lodestone/vision/OrbFeatures.h>
#include <lodestone/vision/RgbdFrame.h>
#include <lodestone/vision/depth/DepthCloud.h>

#include <optional>

namespace lodestone::vision {

/** What visual odometry computes from one frame alone, before it knows anything of the track:
 * the frame, its ORB features with depth and, where the odometry aligns depth, its sampled depth
 * cloud (RgbdVisualOdometry::prepare). They are functions of the frame and the odometry's
 * parameters only, so they may be computed ahead on another thread (lodestone-slam's
 * decode-ahead workers) while the frame loop aligns the frame before: the result is the same. */
struct PreparedFrame {
    RgbdFrame frame;
    FrameFeatures features;
    std::optional<DepthCloud> cloud;  ///< sampled ahead; else sampled when the odometry needs it
    double orbMs{0}, cloudMs{0};      ///< what each cost [ms], on whichever thread ran it
};

}  // namespace lodestone::vision
