#include <lodestone/graphslam/nrd/KeyframeCloud.h>
#include <lodestone/odometry/RgbdObservationFrame.h>

#include <cmath>

namespace lodestone::graphslam {

KeyframeCloud makeKeyframeCloud(const mrpt::obs::CObservation3DRangeScan& obs, int pixelStep,
                                double maxDepth) {
    KeyframeCloud cloud;
    const vision::RgbdFrame frame = odometry::frameFromObservation(obs);
    if (frame.depth.empty() || pixelStep <= 0) return cloud;
    cv::Mat colour;
    if (obs.hasIntensityImage && !obs.intensityImage.isEmpty()) {
        colour = obs.intensityImage.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
    }
    const bool sameSize = !colour.empty() && colour.rows == frame.depth.rows &&
                          colour.cols == frame.depth.cols;
    const Eigen::Isometry3f T_robot_optical = odometry::opticalFrameOnRobot(obs.sensorPose).cast<float>();
    const auto& K = frame.intrinsics;
    for (int v = 0; v < frame.depth.rows; v += pixelStep) {
        const float* row = frame.depth.ptr<float>(v);
        for (int u = 0; u < frame.depth.cols; u += pixelStep) {
            const float z = row[u];
            if (!(z > 0) || z > maxDepth) continue;  // also drops NaN
            const Eigen::Vector3f optical(static_cast<float>((u - K.cx) * z / K.fx),
                                          static_cast<float>((v - K.cy) * z / K.fy), z);
            const Eigen::Vector3f p = T_robot_optical * optical;
            KeyframeCloud::Point pt{p.x(), p.y(), p.z(), 128, 128, 128};
            if (sameSize && colour.channels() == 3) {
                const auto bgr = colour.at<cv::Vec3b>(v, u);
                pt.r = bgr[2];
                pt.g = bgr[1];
                pt.b = bgr[0];
            } else if (sameSize && colour.channels() == 1) {
                pt.r = pt.g = pt.b = colour.at<std::uint8_t>(v, u);
            }
            cloud.points.push_back(pt);
        }
    }
    return cloud;
}

std::shared_ptr<const vision::DepthCloud> makeKeyframeDepth(
    const mrpt::obs::CObservation3DRangeScan& obs, const vision::DepthSampling& sampling) {
    return std::make_shared<vision::DepthCloud>(
        vision::sampleDepthCloud(odometry::frameFromObservation(obs), sampling));
}

}  // namespace lodestone::graphslam
