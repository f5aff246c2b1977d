#include <lodestone/odometry/RgbdObservationFrame.h>

#include <opencv2/imgproc.hpp>

namespace lodestone::odometry {

vision::RgbdFrame frameFromObservation(const mrpt::obs::CObservation3DRangeScan& obs) {
    if (obs.hasRangeImage && !obs.range_is_depth) {
        throw std::invalid_argument("RGB-D observation '" + obs.sensorLabel +
                                    "': range image holds ranges, not depth (range_is_depth)");
    }
    obs.load();
    vision::RgbdFrame f;
    f.timestamp = mrpt::Clock::toDouble(obs.timestamp);
    const auto& cam = obs.cameraParams;
    f.intrinsics = {cam.fx(),
                    cam.fy(),
                    cam.cx(),
                    cam.cy(),
                    static_cast<int>(cam.ncols),
                    static_cast<int>(cam.nrows)};
    if (obs.hasIntensityImage && !obs.intensityImage.isEmpty()) {
        const cv::Mat img = obs.intensityImage.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
        if (img.channels() == 3) {
            cv::cvtColor(img, f.gray, cv::COLOR_BGR2GRAY);
        } else {
            f.gray = img.clone();
        }
    }
    if (obs.hasRangeImage && obs.rangeImage.rows() > 0) {
        const auto& r = obs.rangeImage;
        f.depth.create(static_cast<int>(r.rows()), static_cast<int>(r.cols()), CV_32F);
        const float units = obs.rangeUnits;
        for (int y = 0; y < f.depth.rows; ++y) {
            auto* row = f.depth.ptr<float>(y);
            for (int x = 0; x < f.depth.cols; ++x) row[x] = r(y, x) * units;
        }
    }
    return f;
}

Eigen::Isometry3d opticalFrameOnRobot(const mrpt::poses::CPose3D& sensorPose) {
    // Columns: the optical x (right), y (down), z (forward) axes in MRPT's depth frame.
    Eigen::Matrix3d R_depth_optical;
    R_depth_optical << 0, 0, 1,  //
        -1, 0, 0,                //
        0, -1, 0;
    Eigen::Isometry3d T_robot_depth = Eigen::Isometry3d::Identity();
    T_robot_depth.linear() = sensorPose.getRotationMatrix().asEigen();
    T_robot_depth.translation() = Eigen::Vector3d(sensorPose.x(), sensorPose.y(), sensorPose.z());
    Eigen::Isometry3d T_depth_optical = Eigen::Isometry3d::Identity();
    T_depth_optical.linear() = R_depth_optical;
    return T_robot_depth * T_depth_optical;
}

}  // namespace lodestone::odometry
