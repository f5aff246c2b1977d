#pragma once
// The volume behind TsdfFusion: ours (VoxelBlockVolume) or Open3D's ScalableTSDFVolume, kept
// side by side so the choice stays measurable ([dense] volume).

#include <lodestone/dense/DenseParams.h>
#include <lodestone/dense/Mesh.h>
#include <lodestone/vision/RgbdFrame.h>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include <memory>

namespace lodestone::dense::detail {

class FusionVolume {
  public:
    virtual ~FusionVolume() = default;
    /** `depth`: CV_32FC1 metres, 0 where a pixel is not to be fused; `colourBgr` CV_8UC3 or
     * empty. sign -1 takes a frame out again (where the volume can). */
    virtual void integrate(const cv::Mat& depth, const cv::Mat& colourBgr, const vision::CameraIntrinsics& K,
                           const Eigen::Isometry3d& T_world_optical, int sign) = 0;
    virtual bool canDeintegrate() const = 0;
    virtual Mesh extractMesh() const = 0;
    /** The volume's own memory [bytes] (0: it does not say). */
    virtual std::size_t memoryBytes() const = 0;
};

std::unique_ptr<FusionVolume> makeBlockVolume(const DenseParams& params);
std::unique_ptr<FusionVolume> makeOpen3dVolume(const DenseParams& params);

}  // namespace lodestone::dense::detail
