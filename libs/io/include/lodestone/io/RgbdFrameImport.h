#pragma once

#include <lodestone/io/RawlogWriter.h>

#include <string>

namespace lodestone::io {

/** Pinhole intrinsics [px]. */
struct PinholeIntrinsics {
    double fx{525.0}, fy{525.0}, cx{319.5}, cy{239.5};
};

/** How a dataset's RGB-D frame becomes a CObservation3DRangeScan. */
struct RgbdFrameOptions {
    PinholeIntrinsics intrinsics;
    double depthScale{5000.0};  ///< depth image units per metre (TUM 5000; 7-Scenes, ICL-NUIM 1000)
    /** A depth value this large or larger means "no depth" (7-Scenes writes 65535). */
    unsigned invalidDepthFrom{65535};
    std::string sensorLabel{"RGBD"};
};

/** Writes one frame: the 16-bit depth image embedded (raw values, rangeUnits = 1 / depthScale;
 * values from invalidDepthFrom up become 0, no depth), the colour image referenced in place
 * (absolute path, any format OpenCV reads: PNG, JPEG) as a delay-loaded image; the camera is
 * the robot (sensorPose identity). Throws std::runtime_error naming the file when the colour
 * image is missing or the depth image is missing or not 16-bit. */
void writeRgbdFrame(RawlogWriter& writer, double timestamp, const std::string& colourPath,
                    const std::string& depthPath, const RgbdFrameOptions& options);

}  // namespace lodestone::io
