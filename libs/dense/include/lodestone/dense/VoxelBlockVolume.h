#pragma once

#include <lodestone/dense/Mesh.h>
#include <lodestone/vision/RgbdFrame.h>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

namespace lodestone::dense {

/** A truncated signed distance field with colour in blocks of 8x8x8 voxels, hashed by block so
 * that memory follows the surfaces seen (Niessner et al.'s voxel hashing), each voxel 8 bytes: a
 * 16-bit distance, a 16-bit weight and 8-bit colour. A frame's contribution is a weighted
 * running average (Curless & Levoy) whose weights are integers, so it can be taken out again
 * (de-integration, as BundleFusion does) when the pose it was fused at moves. */
class VoxelBlockVolume {
  public:
    struct Voxel {
        std::int16_t tsdf{0};       ///< distance / truncation, scaled to +-32767
        std::uint16_t weight{0};    ///< sum of the frames' weights (kFullWeight per exact frame)
        std::uint8_t rgb[3]{0, 0, 0};
        std::uint8_t spare{0};
    };
    static constexpr int kSide = 8;  ///< voxels along a block's edge
    static constexpr int kVoxels = kSide * kSide * kSide;
    using Block = std::array<Voxel, kVoxels>;
    /** A pixel at the depth noise model's best (min_depth) weighs this much; farther ones less,
     * as 1/sigma^2, never below 1. */
    static constexpr int kFullWeight = 16;

    /** The grid, and the depth's noise model weighing each pixel: sigma = noiseFloor +
     * depthNoise z^2 [m]. (Which pixels are fused is the caller's: TsdfFusion's range.) */
    struct Settings {
        double voxelSize{0.01};   ///< [m]
        double truncation{0.04};  ///< [m]
        double nearest{0.3};      ///< [m] the depth at which a pixel weighs kFullWeight
        double depthNoise{1.425e-3};
        double noiseFloor{0.002};
    };

    explicit VoxelBlockVolume(const Settings& settings);

    /** Adds (sign +1) or takes out (sign -1) one frame: `depth` CV_32FC1 metres (unusable pixels
     * already 0), `colourBgr` CV_8UC3 of the same size or empty (grey). Taking out a frame with
     * the same depth, colour and pose it was added with restores the field to within rounding.
     * Returns the blocks the frame touched. */
    std::size_t integrate(const cv::Mat& depth, const cv::Mat& colourBgr, const vision::CameraIntrinsics& K,
                          const Eigen::Isometry3d& T_world_optical, int sign = +1);

    /** Marching cubes over every cube whose eight corners have been observed. */
    Mesh extractMesh() const;

    std::size_t blockCount() const { return blocks_.size(); }
    /** The field's memory: its blocks and their hash. */
    std::size_t memoryBytes() const;
    /** The voxel whose centre is nearest to `p` (nullptr where no block is allocated). */
    const Voxel* voxelAt(const Eigen::Vector3d& p) const;
    const Settings& settings() const { return settings_; }

  private:
    static std::uint64_t keyOf(const Eigen::Vector3i& block);
    /** The block's index, allocated when absent. */
    std::uint32_t touch(const Eigen::Vector3i& block);
    const Block* find(const Eigen::Vector3i& block) const;
    void updateBlock(std::uint32_t index, const cv::Mat& depth, const cv::Mat& colourBgr,
                     const vision::CameraIntrinsics& K, const Eigen::Isometry3d& T_optical_world, int sign, const cv::Mat& weights);

    Settings settings_;
    std::vector<std::unique_ptr<Block>> blocks_;
    std::vector<Eigen::Vector3i> coords_;  ///< each block's coordinates (in blocks)
    std::unordered_map<std::uint64_t, std::uint32_t> index_;
    std::vector<std::uint32_t> stamp_;  ///< the last frame that touched each block
    std::uint32_t frame_{0};

    friend class BlockMesher;
};

}  // namespace lodestone::dense
