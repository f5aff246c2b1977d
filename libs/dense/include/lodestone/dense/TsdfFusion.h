#pragma once

#include <lodestone/dense/DenseParams.h>
#include <lodestone/vision/RgbdFrame.h>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lodestone::dense {

/** A coloured triangle mesh. */
struct Mesh {
    std::vector<Eigen::Vector3f> vertices;
    std::vector<std::array<std::uint8_t, 3>> colours;  ///< RGB per vertex
    std::vector<Eigen::Vector3i> triangles;
    bool empty() const { return triangles.empty(); }
};

/** Writes `mesh` as a binary little-endian PLY (float x y z, uchar red green blue per vertex;
 * uchar-counted int vertex indices per face), first to PATH.partial, then renamed. Throws
 * std::runtime_error naming the file when it cannot be written. */
void writeMeshPly(const std::string& path, const Mesh& mesh);

/** Volumetric fusion of RGB-D frames into a truncated signed distance field with colour,
 * voxel-hashed so that memory follows the surfaces seen, not the bounding box (Open3D's
 * ScalableTSDFVolume; Curless & Levoy's weighted average), and meshed by marching cubes. */
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

    /** Marching cubes over the field so far. */
    Mesh extractMesh() const;

    std::size_t framesFused() const { return frames_; }
    const DenseParams& params() const { return params_; }

  private:
    struct Volume;
    DenseParams params_;
    std::unique_ptr<Volume> volume_;
    std::size_t frames_{0};
};

}  // namespace lodestone::dense
