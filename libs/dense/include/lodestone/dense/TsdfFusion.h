#pragma once

#include <lodestone/dense/DenseParams.h>
#include <lodestone/dense/Mesh.h>
#include <lodestone/vision/RgbdFrame.h>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lodestone::dense {

namespace detail {
class FusionVolume;
}

/** Volumetric fusion of RGB-D frames into a truncated signed distance field with colour,
 * voxel-hashed so that memory follows the surfaces seen, not the bounding box (Curless & Levoy's
 * weighted average), and meshed by marching cubes. The volume is ours (`VoxelBlockVolume`,
 * which can take a frame out again) or Open3D's `ScalableTSDFVolume` ([dense] volume). */
class TsdfFusion {
  public:
    explicit TsdfFusion(const DenseParams& params);
    ~TsdfFusion();
    TsdfFusion(const TsdfFusion&) = delete;
    TsdfFusion& operator=(const TsdfFusion&) = delete;

    /** Fuses one frame: `depth` CV_32FC1 in metres along z, `colourBgr` CV_8UC3 of the same
     * size (empty: grey), the camera's optical frame (x right, y down, z forward) in the world.
     * Pixels without depth (0, NaN, infinite, negative) or outside [min_depth, the noise
     * model's limit] are not fused. Returns the pixels fused (0 for a frame with no usable
     * depth: it changes nothing). Throws std::invalid_argument for images of the wrong type
     * or size. */
    std::size_t integrate(const cv::Mat& depth, const cv::Mat& colourBgr,
                          const vision::CameraIntrinsics& intrinsics,
                          const Eigen::Isometry3d& T_world_optical);

    /** Takes out a frame fused before, given the same images and the pose it was fused at
     * (BundleFusion's de-integration): then fusing it at a moved pose gives the model fusing
     * it there first would have. Throws std::logic_error for Open3D's volume, which cannot. */
    std::size_t deintegrate(const cv::Mat& depth, const cv::Mat& colourBgr,
                            const vision::CameraIntrinsics& intrinsics,
                            const Eigen::Isometry3d& T_world_optical);

    /** Marching cubes over the field so far. */
    Mesh extractMesh() const;

    /** Frames fused and not taken out. */
    std::size_t framesFused() const { return static_cast<std::size_t>(frames_); }
    /** The volume's own memory [bytes]; 0 for Open3D's, which does not say. */
    std::size_t memoryBytes() const;
    const DenseParams& params() const { return params_; }

  private:
    std::size_t fuse(const cv::Mat& depth, const cv::Mat& colourBgr, const vision::CameraIntrinsics& intrinsics,
                     const Eigen::Isometry3d& T_world_optical, int sign);

    DenseParams params_;
    std::unique_ptr<detail::FusionVolume> volume_;
    long frames_{0};
};

}  // namespace lodestone::dense
