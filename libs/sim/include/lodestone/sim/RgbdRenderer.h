#pragma once

#include <lodestone/sim/Random.h>
#include <lodestone/sim/Scenario.h>
#include <lodestone/sim/World.h>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

namespace lodestone::sim {

/** Renders what an RGB-D camera sees in the world. Walls are vertical extrusions, so for a level
 * camera each image column is one 2D ray cast (a tilted one casts one per pixel); every pixel of the column is then a wall, floor or ceiling
 * point found in closed form. Depth gets Kinect-like noise (sigma = k z^2, Khoshelham & Elberink
 * 2012), the disparity quantization of structured light (depth steps of q z^2), millimetre
 * units, and no value beyond the range limits or at grazing angles;
 * colour gets per-channel noise. */
class RgbdRenderer {
  public:
    RgbdRenderer(const World& world, const CameraSpec& camera, std::uint64_t noiseSeed);

    /** Renders from a camera at `position` [m] with heading `yaw` [rad] (optical axis level).
     * `depth` is in millimetres along the optical axis, 0 where invalid; `rgb` is BGR. */
    void render(const Eigen::Vector3d& position, double yaw, Random& rng, cv::Mat3b& rgb,
                cv::Mat_<uint16_t>& depth) const;
    /** The same from any camera pose (world <- camera in MRPT's depth frame: x forward, y
     * left, z up), tilted as a hand-held camera is. */
    void render(const Eigen::Isometry3d& pose, Random& rng, cv::Mat3b& rgb,
                cv::Mat_<uint16_t>& depth) const;

    /** The share of image columns whose wall, within the depth range, is textured (not plain
     * paint): what the camera has to work with, from the ground truth of the world. */
    double texturedFraction(const Eigen::Vector3d& position, double yaw) const;

    /** Noise-free depth [m] along the optical axis for one pixel, NaN if nothing is seen
     * within the range limits (for tests). */
    double idealDepth(const Eigen::Vector3d& position, double yaw, int row, int col) const;

  private:
    struct Surface {
        double depth;   // along the optical axis [m]
        double cosInc;  // |cos| of the incidence angle
        cv::Vec3f colour;
        bool valid;
    };
    /** `pixel` holds the ray's change across one pixel (a column step, a row step): the
     * pixel's footprint on the surface, over which its colour is averaged. */
    struct PixelSteps {
        Eigen::Vector3d column, row;
    };
    Surface trace(const Eigen::Vector3d& position, const Eigen::Vector2d& h,
                  const std::optional<WallHit>& wall, double b, const PixelSteps& pixel) const;

    const World& world_;
    CameraSpec camera_;
    NoiseTable noise_;
    double cos_max_incidence_;
};

}  // namespace lodestone::sim
