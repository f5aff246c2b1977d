#include "FusionVolume.h"

#include <lodestone/dense/TsdfFusion.h>
#include <lodestone/dense/VoxelBlockVolume.h>

#include <cmath>
#include <stdexcept>

namespace lodestone::dense {

namespace detail {

namespace {

class BlockVolume : public FusionVolume {
  public:
    explicit BlockVolume(const DenseParams& p)
        : volume_({p.voxelSize, p.truncation, p.minDepth, p.depthNoise, p.noiseFloor}) {}
    void integrate(const cv::Mat& depth, const cv::Mat& colourBgr, const vision::CameraIntrinsics& K,
                   const Eigen::Isometry3d& T_world_optical, int sign) override {
        volume_.integrate(depth, colourBgr, K, T_world_optical, sign);
    }
    bool canDeintegrate() const override { return true; }
    Mesh extractMesh() const override { return volume_.extractMesh(); }
    std::size_t memoryBytes() const override { return volume_.memoryBytes(); }

  private:
    VoxelBlockVolume volume_;
};

}  // namespace

std::unique_ptr<FusionVolume> makeBlockVolume(const DenseParams& params) {
    return std::make_unique<BlockVolume>(params);
}

}  // namespace detail

TsdfFusion::TsdfFusion(const DenseParams& params)
    : params_(params),
      volume_(params.volume == DenseParams::Volume::Open3d ? detail::makeOpen3dVolume(params)
                                                           : detail::makeBlockVolume(params)) {}

TsdfFusion::~TsdfFusion() = default;

std::size_t TsdfFusion::integrate(const cv::Mat& depth, const cv::Mat& colourBgr,
                                  const vision::CameraIntrinsics& intrinsics,
                                  const Eigen::Isometry3d& T_world_optical) {
    return fuse(depth, colourBgr, intrinsics, T_world_optical, +1);
}

std::size_t TsdfFusion::deintegrate(const cv::Mat& depth, const cv::Mat& colourBgr,
                                    const vision::CameraIntrinsics& intrinsics,
                                    const Eigen::Isometry3d& T_world_optical) {
    if (!volume_->canDeintegrate())
        throw std::logic_error("dense fusion: this volume cannot take a frame out ([dense] volume = blocks can)");
    return fuse(depth, colourBgr, intrinsics, T_world_optical, -1);
}

std::size_t TsdfFusion::fuse(const cv::Mat& depth, const cv::Mat& colourBgr,
                             const vision::CameraIntrinsics& intrinsics,
                             const Eigen::Isometry3d& T_world_optical, int sign) {
    if (depth.type() != CV_32FC1) throw std::invalid_argument("dense fusion: depth must be CV_32FC1 metres");
    if (!colourBgr.empty() && (colourBgr.type() != CV_8UC3 || colourBgr.size() != depth.size()))
        throw std::invalid_argument("dense fusion: colour must be CV_8UC3 of the depth's size");
    if (depth.cols != intrinsics.width || depth.rows != intrinsics.height)
        throw std::invalid_argument("dense fusion: depth " + std::to_string(depth.cols) + "x" +
                                    std::to_string(depth.rows) + " against intrinsics " +
                                    std::to_string(intrinsics.width) + "x" + std::to_string(intrinsics.height));
    const float near = static_cast<float>(params_.minDepth);
    const float far = static_cast<float>(params_.fusedDepthLimit());
    cv::Mat usable(depth.size(), CV_32FC1);
    std::size_t pixels = 0;
    for (int y = 0; y < depth.rows; ++y) {
        const float* in = depth.ptr<float>(y);
        float* out = usable.ptr<float>(y);
        for (int x = 0; x < depth.cols; ++x) {
            const float z = in[x];
            const bool ok = std::isfinite(z) && z >= near && z <= far;
            out[x] = ok ? z : 0.0f;
            pixels += ok;
        }
    }
    if (pixels == 0) return 0;
    volume_->integrate(usable, colourBgr, intrinsics, T_world_optical, sign);
    frames_ += sign;
    return pixels;
}

Mesh TsdfFusion::extractMesh() const { return frames_ == 0 ? Mesh{} : volume_->extractMesh(); }

std::size_t TsdfFusion::memoryBytes() const { return volume_->memoryBytes(); }

}  // namespace lodestone::dense
