#pragma once

#include <lodestone/vision/RgbdFrame.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <Eigen/Geometry>

namespace lodestone::odometry {

/** The vision library's frame from an MRPT RGB-D observation: grey image, depth in metres
 * (rangeImage x rangeUnits), depth intrinsics (colour and depth assumed registered). Loads
 * delay-loaded images. A frame without an image or depth comes back with that part empty (the
 * odometry then fails on it instead of crashing). Throws std::invalid_argument for range
 * images that are not depth (range_is_depth = false). */
vision::RgbdFrame frameFromObservation(const mrpt::obs::CObservation3DRangeScan& obs);

/** The camera's optical frame (x right, y down, z forward) in the robot frame, from the
 * observation's sensorPose (MRPT's depth frame: x forward, y left, z up). */
Eigen::Isometry3d opticalFrameOnRobot(const mrpt::poses::CPose3D& sensorPose);

}  // namespace lodestone::odometry
