#pragma once

#include <lodestone/datasets/RgbdFrameImport.h>

#include <optional>
#include <string>

namespace lodestone::datasets {

struct SevenScenesImportOptions {
    /** Unset: `camera-intrinsics.txt` (a 3 x 3 matrix, 3DMatch's layout) in the sequence
     * folder or its parent, else 7-Scenes' published 585, 585, 320, 240. */
    std::optional<PinholeIntrinsics> intrinsics;
    double depthScale{1000.0};  ///< depth PNG units per metre (7-Scenes: millimetres)
    double rate{30.0};          ///< [Hz] frames carry no time stamps: frame i is at i / rate
    std::string sensorLabel{"RGBD"};
    std::optional<DepthRegistration> registration;  ///< depth not registered to colour
};

struct SevenScenesImportResult {
    std::size_t frames{0};
    std::size_t groundTruthPoses{0};  ///< frames with a finite pose (3DMatch marks unknown ones -inf)
    PinholeIntrinsics intrinsics;     ///< what was used
    std::string intrinsicsSource;     ///< "--intrinsics", the file read, or "7-Scenes default"
    std::string rawlog, groundTruth;
};

/** Converts a 7-Scenes / 3DMatch sequence folder (frame-NNNNNN.color.png or .color.jpg,
 * frame-NNNNNN.depth.png in millimetres with 65535 for no depth, frame-NNNNNN.pose.txt: the
 * 4 x 4 camera-to-world matrix) into an observation-only rawlog of CObservation3DRangeScan,
 * frames in index order, and the poses into OUT.gt.tum. Frames are written as TUM's are
 * (RgbdFrameImport). Throws std::runtime_error naming the file (and line) for a folder with no
 * frames, a missing depth image, a malformed pose or intrinsics file; frames already written
 * stay in the rawlog. */
SevenScenesImportResult importSevenScenes(const std::string& sequenceDir, const std::string& outRawlog,
                                          const SevenScenesImportOptions& options);

/** A 3 x 3 camera matrix file (fx 0 cx / 0 fy cy / 0 0 1). Throws std::runtime_error naming
 * the file otherwise. */
PinholeIntrinsics readCameraMatrix(const std::string& path);

}  // namespace lodestone::datasets
