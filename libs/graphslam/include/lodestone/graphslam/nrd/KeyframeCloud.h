#pragma once

#include <lodestone/vision/depth/DepthCloud.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace lodestone::graphslam {

/** A coloured point cloud of one keyframe, in the robot frame of its node: what map.ply is built
 * from once the node poses are optimized. */
struct KeyframeCloud {
    struct Point {
        float x, y, z;
        std::uint8_t r, g, b;
    };
    std::vector<Point> points;
};

/** Every `pixelStep`-th depth pixel (in both directions) with a depth in (0, maxDepth], coloured
 * from the intensity image (grey when there is none), moved to the robot frame with the
 * observation's sensorPose. A frame without depth gives an empty cloud. */
KeyframeCloud makeKeyframeCloud(const mrpt::obs::CObservation3DRangeScan& obs, int pixelStep,
                                double maxDepth);

/** A keyframe's depth as VO's depth alignment samples it (`sampling`), in its optical frame:
 * what NodeRecord::depth holds where a loop closer asks for it. */
std::shared_ptr<const vision::DepthCloud> makeKeyframeDepth(
    const mrpt::obs::CObservation3DRangeScan& obs, const vision::DepthSampling& sampling);

}  // namespace lodestone::graphslam
