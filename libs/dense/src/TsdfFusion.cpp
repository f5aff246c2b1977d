#include <lodestone/dense/TsdfFusion.h>

#include <open3d/camera/PinholeCameraIntrinsic.h>
#include <open3d/geometry/Image.h>
#include <open3d/geometry/RGBDImage.h>
#include <open3d/geometry/TriangleMesh.h>
#include <open3d/pipelines/integration/ScalableTSDFVolume.h>

#include <cmath>
#include <stdexcept>

namespace lodestone::dense {

struct TsdfFusion::Volume {
    open3d::pipelines::integration::ScalableTSDFVolume tsdf;
    Volume(double voxel, double truncation)
        : tsdf(voxel, truncation, open3d::pipelines::integration::TSDFVolumeColorType::RGB8) {}
};

TsdfFusion::TsdfFusion(const DenseParams& params)
    : params_(params), volume_(std::make_unique<Volume>(params.voxelSize, params.truncation)) {}

TsdfFusion::~TsdfFusion() = default;

std::size_t TsdfFusion::integrate(const cv::Mat& depth, const cv::Mat& colourBgr,
                                  const vision::CameraIntrinsics& intrinsics,
                                  const Eigen::Isometry3d& T_world_optical) {
    if (depth.type() != CV_32FC1) throw std::invalid_argument("dense fusion: depth must be CV_32FC1 metres");
    if (!colourBgr.empty() && (colourBgr.type() != CV_8UC3 || colourBgr.size() != depth.size()))
        throw std::invalid_argument("dense fusion: colour must be CV_8UC3 of the depth's size");
    if (depth.cols != intrinsics.width || depth.rows != intrinsics.height)
        throw std::invalid_argument("dense fusion: depth " + std::to_string(depth.cols) + "x" +
                                    std::to_string(depth.rows) + " against intrinsics " +
                                    std::to_string(intrinsics.width) + "x" + std::to_string(intrinsics.height));
    const float near = static_cast<float>(params_.minDepth);
    const float far = static_cast<float>(params_.fusedDepthLimit());
    open3d::geometry::Image d, c;
    d.Prepare(depth.cols, depth.rows, 1, 4);
    c.Prepare(depth.cols, depth.rows, 3, 1);
    std::size_t usable = 0;
    for (int y = 0; y < depth.rows; ++y) {
        const float* in = depth.ptr<float>(y);
        float* out = d.PointerAt<float>(0, y);
        const cv::Vec3b* bgr = colourBgr.empty() ? nullptr : colourBgr.ptr<cv::Vec3b>(y);
        std::uint8_t* rgb = c.PointerAt<std::uint8_t>(0, y, 0);
        for (int x = 0; x < depth.cols; ++x) {
            const float z = in[x];
            const bool ok = std::isfinite(z) && z >= near && z <= far;
            out[x] = ok ? z : 0.0f;
            usable += ok;
            rgb[3 * x + 0] = bgr ? bgr[x][2] : 128;
            rgb[3 * x + 1] = bgr ? bgr[x][1] : 128;
            rgb[3 * x + 2] = bgr ? bgr[x][0] : 128;
        }
    }
    if (usable == 0) return 0;
    const auto rgbd = open3d::geometry::RGBDImage::CreateFromColorAndDepth(c, d, 1.0, far, false);
    const open3d::camera::PinholeCameraIntrinsic K(intrinsics.width, intrinsics.height, intrinsics.fx,
                                                   intrinsics.fy, intrinsics.cx, intrinsics.cy);
    // (Open3D's extrinsic maps the world into the camera)
    volume_->tsdf.Integrate(*rgbd, K, T_world_optical.inverse().matrix());
    ++frames_;
    return usable;
}

Mesh TsdfFusion::extractMesh() const {
    Mesh m;
    if (frames_ == 0) return m;
    const auto mesh = const_cast<Volume&>(*volume_).tsdf.ExtractTriangleMesh();
    m.vertices.reserve(mesh->vertices_.size());
    for (std::size_t i = 0; i < mesh->vertices_.size(); ++i) {
        m.vertices.push_back(mesh->vertices_[i].cast<float>());
        const Eigen::Vector3d col = i < mesh->vertex_colors_.size() ? mesh->vertex_colors_[i] : Eigen::Vector3d(0.5, 0.5, 0.5);
        m.colours.push_back({static_cast<std::uint8_t>(std::lround(255 * std::clamp(col.x(), 0.0, 1.0))),
                             static_cast<std::uint8_t>(std::lround(255 * std::clamp(col.y(), 0.0, 1.0))),
                             static_cast<std::uint8_t>(std::lround(255 * std::clamp(col.z(), 0.0, 1.0)))});
    }
    m.triangles = mesh->triangles_;
    return m;
}

}  // namespace lodestone::dense
