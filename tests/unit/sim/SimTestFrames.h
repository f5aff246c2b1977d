#pragma once

#include <lodestone/sim/RgbdRenderer.h>
#include <lodestone/vision/RgbdFrame.h>

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

namespace lodestone::test {

/** The optical frame (x right, y down, z forward) in MRPT's depth frame (x forward, y left, z up). */
inline Eigen::Isometry3d opticalInCamera() {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
    return T;
}

/** A camera pose in the world (MRPT's depth frame) at `p`, turned by yaw, pitch (down +), roll. */
inline Eigen::Isometry3d cameraPose(const Eigen::Vector3d& p, double yaw, double pitch = 0,
                                    double roll = 0) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    T.translation() = p;
    return T;
}

/** The simulator's default camera's frame at a camera pose (MRPT's depth frame, world). */
inline vision::RgbdFrame render(const sim::World& world, const Eigen::Isometry3d& pose,
                                std::uint64_t seed) {
    sim::CameraSpec cam;
    sim::RgbdRenderer renderer(world, cam, seed);
    sim::Random rng(seed);
    cv::Mat3b rgb;
    cv::Mat_<uint16_t> depth;
    renderer.render(pose, rng, rgb, depth);
    vision::RgbdFrame f;
    cv::cvtColor(rgb, f.gray, cv::COLOR_BGR2GRAY);
    f.depth = vision::depthToMetres(depth, 0.001);
    f.intrinsics = {cam.fx, cam.fy, cam.cx, cam.cy, cam.width, cam.height};
    return f;
}

}  // namespace lodestone::test
