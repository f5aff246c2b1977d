#pragma once
// 3DMatch seq-01's real Kinect frames (a kitchen, ../shared/data/rgbd/3dmatch: frames 0, 1, 2,
// 116, 422), read in place: tests skip where the folder is absent.

#include <lodestone/vision/RgbdFrame.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "TestPaths.h"

namespace lodestone::test {

inline std::filesystem::path threeDMatchDir() {
    return sharedDataDir() / "rgbd" / "3dmatch";
}

/** Frame `index`'s grey image and depth, with the sequence's intrinsics. */
inline vision::RgbdFrame threeDMatchFrame(int index) {
    char name[64];
    std::snprintf(name, sizeof(name), "seq-01/frame-%06d", index);
    const auto dir = threeDMatchDir();
    vision::RgbdFrame f;
    const cv::Mat colour = cv::imread((dir / (std::string(name) + ".color.png")).string());
    cv::cvtColor(colour, f.gray, cv::COLOR_BGR2GRAY);
    const cv::Mat depth =
        cv::imread((dir / (std::string(name) + ".depth.png")).string(), cv::IMREAD_UNCHANGED);
    f.depth = vision::depthToMetres(depth, 0.001);
    f.intrinsics = {570.342205, 570.342205, 320.0, 240.0, 640, 480};
    return f;
}

/** Frame `index`'s camera-to-world pose (from the reconstruction). */
inline Eigen::Isometry3d threeDMatchPose(int index) {
    char name[64];
    std::snprintf(name, sizeof(name), "seq-01/frame-%06d.pose.txt", index);
    std::ifstream in(threeDMatchDir() / name);
    Eigen::Matrix4d m;
    for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) in >> m(r, c);
    }
    Eigen::Isometry3d T;
    T.matrix() = m;
    return T;
}

}  // namespace lodestone::test
