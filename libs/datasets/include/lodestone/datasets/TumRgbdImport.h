#pragma once

#include <lodestone/datasets/RgbdFrameImport.h>

#include <optional>
#include <string>

namespace lodestone::datasets {

/** Pinhole intrinsics the TUM RGB-D sequences were recorded with [px]. */
struct TumIntrinsics : PinholeIntrinsics {
    /** "fr1", "fr2", "fr3" (the TUM calibrations of the colour cameras, to which depth is
     * registered), "default" (ROS's 525/525/319.5/239.5) or "fx,fy,cx,cy". Throws
     * std::invalid_argument naming the text otherwise. */
    static TumIntrinsics parse(const std::string& text);
};

struct TumImportOptions {
    TumIntrinsics intrinsics;
    double maxTimeDifference{0.02};  ///< RGB-depth association tolerance [s]
    double depthScale{5000.0};       ///< depth PNG units per metre (TUM: 5000)
    std::string sensorLabel{"RGBD"};
    std::optional<DepthRegistration> registration;  ///< depth not registered to colour
};

struct TumImportResult {
    std::size_t frames{0};  ///< associated RGB-D pairs written
    std::size_t unmatchedRgb{0}, unmatchedDepth{0};
    std::size_t groundTruthPoses{0};  ///< 0 when the sequence has no groundtruth.txt
    std::string rawlog, groundTruth;
};

/** Converts a TUM RGB-D sequence folder (rgb.txt, depth.txt, optional groundtruth.txt, the
 * images they list) into an observation-only rawlog of CObservation3DRangeScan: each RGB image
 * paired with the depth image nearest in time (within maxTimeDifference, each used once),
 * depth embedded (raw 16-bit values, rangeUnits = 1 / depthScale), colour referenced in place
 * as a delay-loaded image (absolute path, nothing copied). The ground truth, if present, is
 * written beside the rawlog as OUT.gt.tum. Throws std::runtime_error naming the file and line
 * for a missing or malformed list or image; frames already written stay in the rawlog. */
TumImportResult importTumRgbd(const std::string& sequenceDir, const std::string& outRawlog,
                              const TumImportOptions& options);

}  // namespace lodestone::datasets
