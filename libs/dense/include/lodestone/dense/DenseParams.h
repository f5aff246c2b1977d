#pragma once

#include <mrpt/config/CConfigFileBase.h>

#include <string>

namespace lodestone::dense {

/** The dense model's keys (INI section [dense]), each with its unit. */
struct DenseParams {
    double voxelSize{0.01};   ///< [m] edge of a TSDF voxel
    double truncation{0.04};  ///< [m] the signed distance is kept within this of a surface
    double minDepth{0.3};     ///< [m] nearer pixels are not fused
    double maxDepth{5.0};     ///< [m] farther pixels are not fused
    /** The depth's noise model (as VO's: sigma = noise_floor + depth_noise z^2 [m]): a pixel
     * whose sigma exceeds half the truncation band would blur the surface it lands on, and is
     * not fused - the model cuts the depth range where it stops being exact enough. */
    double depthNoise{1.425e-3};  ///< [1/m]
    double noiseFloor{0.002};     ///< [m]
    int everyKeyframe{1};         ///< fuse every n-th keyframe's frame
    /** The volume: ours (8^3-voxel blocks, 8 bytes a voxel, can take a frame out) or Open3D's
     * ScalableTSDFVolume (kept to measure against). */
    enum class Volume { Blocks, Open3d } volume{Volume::Blocks};
    /** When an offline run fuses: after its last optimization, reading its frames again
     * (after_run), or as it makes keyframes, re-fusing those the graph moves (while_running,
     * as a live run always does). */
    enum class Fusion { AfterRun, WhileRunning } fusion{Fusion::AfterRun};

    /** The farthest depth fused: max_depth, or nearer where the noise model says so. */
    double fusedDepthLimit() const;
    /** Reads [dense] strictly (unknown keys, values out of range: config::ConfigError naming the
     * key); a missing section leaves the defaults. */
    static DenseParams read(const mrpt::config::CConfigFileBase& ini);
};

}  // namespace lodestone::dense
