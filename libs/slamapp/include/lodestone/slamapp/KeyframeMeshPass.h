#pragma once

#include <lodestone/dense/TsdfFusion.h>
#include <lodestone/io/DataSource.h>

#include <Eigen/Geometry>

#include <map>

namespace lodestone::slamapp {

/** What a pass over a source fused. */
struct KeyframeMeshPass {
    std::size_t keyframes{0};     ///< asked for
    std::size_t framesFound{0};   ///< RGB-D frames of the source at a keyframe's time
    std::size_t withoutDepth{0};  ///< found, but no usable depth
    std::size_t pixels{0};        ///< fused
    double integrateSeconds{0};
};

/** Reads `source` to the last keyframe's time and fuses every CObservation3DRangeScan whose
 * time is a keyframe's (within 0.1 ms) at that keyframe's robot pose (`robotPoseByTime`, the
 * frame's own sensor pose on the robot applied) into `fusion`. The pass after a run
 * (lodestone-slam --mesh) and a finished run's folder (lodestone-inspect mesh) share it. */
KeyframeMeshPass fuseKeyframes(io::DataSource& source, const std::map<double, Eigen::Isometry3d>& robotPoseByTime,
                               dense::TsdfFusion& fusion);

}  // namespace lodestone::slamapp
