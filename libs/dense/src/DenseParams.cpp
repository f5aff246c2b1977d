#include <lodestone/config/IniSection.h>
#include <lodestone/dense/DenseParams.h>

#include <algorithm>
#include <cmath>

namespace lodestone::dense {

double DenseParams::fusedDepthLimit() const {
    // noise_floor + depth_noise z^2 <= truncation / 2
    const double room = 0.5 * truncation - noiseFloor;
    if (room <= 0) return 0;
    return std::min(maxDepth, depthNoise > 0 ? std::sqrt(room / depthNoise) : maxDepth);
}

DenseParams DenseParams::read(const mrpt::config::CConfigFileBase& ini) {
    DenseParams p;
    config::IniSection s(ini, "dense", config::sourceName(ini));
    p.voxelSize = s.getDouble("voxel_size", p.voxelSize);
    p.truncation = s.getDouble("truncation", p.truncation);
    p.minDepth = s.getDouble("min_depth", p.minDepth);
    p.maxDepth = s.getDouble("max_depth", p.maxDepth);
    p.depthNoise = s.getDouble("depth_noise", p.depthNoise);
    p.noiseFloor = s.getDouble("noise_floor", p.noiseFloor);
    p.everyKeyframe = s.getInt("every_keyframe", p.everyKeyframe);
    const std::string volume = s.getString("volume", "blocks");
    if (volume == "open3d") p.volume = Volume::Open3d;
    else if (volume != "blocks") s.fail("volume", "must be blocks or open3d, not '" + volume + "'");
    const std::string fusion = s.getString("fusion", "after_run");
    if (fusion == "while_running") p.fusion = Fusion::WhileRunning;
    else if (fusion != "after_run") s.fail("fusion", "must be after_run or while_running, not '" + fusion + "'");
    if (p.fusion == Fusion::WhileRunning && p.volume == Volume::Open3d)
        s.fail("fusion", "while_running takes frames out again: volume = blocks");
    if (!(p.voxelSize >= 0.002 && p.voxelSize <= 0.5)) s.fail("voxel_size", "must be in [0.002, 0.5] m");
    if (!(p.truncation >= 2 * p.voxelSize)) s.fail("truncation", "must be at least two voxels");
    if (!(p.minDepth >= 0 && p.maxDepth > p.minDepth)) s.fail("max_depth", "must be > min_depth >= 0");
    if (!(p.depthNoise >= 0) || !(p.noiseFloor >= 0)) s.fail("depth_noise", "the noise model must be >= 0");
    if (!(p.fusedDepthLimit() > p.minDepth))
        s.fail("truncation", "the depth noise model leaves no depth to fuse within half of it");
    if (p.everyKeyframe < 1) s.fail("every_keyframe", "must be >= 1");
    s.finish();
    return p;
}

}  // namespace lodestone::dense
