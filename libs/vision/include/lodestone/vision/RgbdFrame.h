#pragma once

#include <opencv2/core.hpp>

namespace lodestone::vision {

/** Pinhole intrinsics of a registered RGB-D pair (colour and depth share them). */
struct CameraIntrinsics {
    double fx{570.3}, fy{570.3}, cx{319.5}, cy{239.5};  ///< [px]
    int width{640}, height{480};                        ///< [px]
};

/** One RGB-D frame as the vision algorithms take it. Points are in the camera's optical frame:
 * x right, y down, z forward (OpenCV's convention), in metres. */
struct RgbdFrame {
    cv::Mat gray;   ///< CV_8UC1
    cv::Mat depth;  ///< CV_32FC1 depth along z [m]; 0 or NaN where unknown
    CameraIntrinsics intrinsics;
    double timestamp{0};  ///< [s]
};

/** A frame's depth image in metres from raw 16-bit units (e.g. 0.001 for millimetres). */
cv::Mat depthToMetres(const cv::Mat& raw16, double metresPerUnit);

}  // namespace lodestone::vision
