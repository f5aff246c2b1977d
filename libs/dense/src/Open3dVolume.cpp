// Open3D's ScalableTSDFVolume behind TsdfFusion ([dense] volume = open3d): 16^3-voxel units, a
// float distance and weight and a double colour per voxel; it cannot take a frame out.
#include "FusionVolume.h"

#include <open3d/camera/PinholeCameraIntrinsic.h>
#include <open3d/geometry/Image.h>
#include <open3d/geometry/RGBDImage.h>
#include <open3d/geometry/TriangleMesh.h>
#include <open3d/pipelines/integration/ScalableTSDFVolume.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lodestone::dense::detail {

namespace {

class Open3dVolume : public FusionVolume {
  public:
    explicit Open3dVolume(const DenseParams& p)
        : far_(p.fusedDepthLimit()),
          tsdf_(p.voxelSize, p.truncation, open3d::pipelines::integration::TSDFVolumeColorType::RGB8) {}

    void integrate(const cv::Mat& depth, const cv::Mat& colourBgr, const vision::CameraIntrinsics& K,
                   const Eigen::Isometry3d& T_world_optical, int sign) override {
        if (sign != 1) throw std::logic_error("Open3D's TSDF volume cannot take a frame out (de-integrate)");
        open3d::geometry::Image d, c;
        d.Prepare(depth.cols, depth.rows, 1, 4);
        c.Prepare(depth.cols, depth.rows, 3, 1);
        for (int y = 0; y < depth.rows; ++y) {
            std::copy_n(depth.ptr<float>(y), depth.cols, d.PointerAt<float>(0, y));
            const cv::Vec3b* bgr = colourBgr.empty() ? nullptr : colourBgr.ptr<cv::Vec3b>(y);
            std::uint8_t* rgb = c.PointerAt<std::uint8_t>(0, y, 0);
            for (int x = 0; x < depth.cols; ++x)
                for (int k = 0; k < 3; ++k) rgb[3 * x + k] = bgr ? bgr[x][2 - k] : 128;
        }
        const auto rgbd = open3d::geometry::RGBDImage::CreateFromColorAndDepth(c, d, 1.0, far_, false);
        const open3d::camera::PinholeCameraIntrinsic intrinsic(K.width, K.height, K.fx, K.fy, K.cx, K.cy);
        // (Open3D's extrinsic maps the world into the camera)
        tsdf_.Integrate(*rgbd, intrinsic, T_world_optical.inverse().matrix());
    }

    bool canDeintegrate() const override { return false; }

    Mesh extractMesh() const override {
        Mesh m;
        const auto mesh = const_cast<open3d::pipelines::integration::ScalableTSDFVolume&>(tsdf_).ExtractTriangleMesh();
        m.vertices.reserve(mesh->vertices_.size());
        const auto byte = [](double c) { return static_cast<std::uint8_t>(std::lround(255 * std::clamp(c, 0.0, 1.0))); };
        for (std::size_t i = 0; i < mesh->vertices_.size(); ++i) {
            m.vertices.push_back(mesh->vertices_[i].cast<float>());
            const Eigen::Vector3d col =
                i < mesh->vertex_colors_.size() ? mesh->vertex_colors_[i] : Eigen::Vector3d(0.5, 0.5, 0.5);
            m.colours.push_back({byte(col.x()), byte(col.y()), byte(col.z())});
        }
        m.triangles = mesh->triangles_;
        return m;
    }

    std::size_t memoryBytes() const override { return 0; }

  private:
    double far_;
    open3d::pipelines::integration::ScalableTSDFVolume tsdf_;
};

}  // namespace

std::unique_ptr<FusionVolume> makeOpen3dVolume(const DenseParams& params) {
    return std::make_unique<Open3dVolume>(params);
}

}  // namespace lodestone::dense::detail
