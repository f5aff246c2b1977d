#pragma once

#include <lodestone/datasets/DepthRegistration.h>
#include <lodestone/datasets/PinholeIntrinsics.h>
#include <lodestone/io/RawlogWriter.h>

#include <optional>
#include <string>

namespace lodestone::datasets {

/** How a dataset's RGB-D frame becomes a CObservation3DRangeScan. */
struct RgbdFrameOptions {
    PinholeIntrinsics intrinsics;
    double depthScale{5000.0};  ///< depth image units per metre (TUM 5000; 7-Scenes, ICL-NUIM 1000)
    /** A depth value this large or larger means "no depth" (7-Scenes writes 65535). */
    unsigned invalidDepthFrom{65535};
    std::string sensorLabel{"RGBD"};
    /** Depth not registered to colour: moved into the colour camera on import (the rawlog's
     * depth is then colour-sized and shares `intrinsics`). */
    std::optional<DepthRegistration> registration;
};

/** Writes one frame: the 16-bit depth image (registered to colour first, if asked) embedded (raw values, rangeUnits = 1 / depthScale;
 * values from invalidDepthFrom up become 0, no depth), the colour image referenced in place
 * (absolute path, any format OpenCV reads: PNG, JPEG) as a delay-loaded image; the camera is
 * the robot (sensorPose identity). Throws std::runtime_error naming the file when the colour
 * image is missing or the depth image is missing or not 16-bit. */
void writeRgbdFrame(io::RawlogWriter& writer, double timestamp, const std::string& colourPath,
                    const std::string& depthPath, const RgbdFrameOptions& options);

}  // namespace lodestone::datasets
