#pragma once

#include <lodestone/sim/Random.h>

#include <functional>
#include <opencv2/core.hpp>
#include <string>

namespace lodestone::sim {

/** How a surface looks. Posters and bricks are rich in corners (ORB finds hundreds); plain is
 * paint with mild shading, where RGB-D odometry starves; tiles cover floors. */
enum class SurfaceStyle { Posters, Bricks, Plain, Tiles, Image };

struct SurfaceSpec {
    SurfaceStyle style{SurfaceStyle::Plain};
    cv::Vec3b baseColor{175, 182, 190};  ///< BGR, for plain / tiles / posters background
    std::string imagePath;               ///< Image style: a photo, tiled
    double imageWidth{1.0};              ///< Image style: the photo's width on the wall [m]

    /** "posters", "bricks", "plain", "tiles", or "image:<path>:<width m>"; throws
     * std::invalid_argument naming the text otherwise. */
    static SurfaceSpec parse(const std::string& text);
};

/** An albedo raster of one surface (a wall side, the floor, the ceiling), in metres: u along
 * the surface, v across (up for walls). Lighting is baked in, so rendering is a lookup. */
class SurfaceTexture {
  public:
    SurfaceTexture() = default;
    /** A width x height [m] raster at `pixelsPerMetre`, drawn from `spec` with `rng`. */
    static SurfaceTexture generate(const SurfaceSpec& spec, double width, double height,
                                   double pixelsPerMetre, Random& rng);

    /** Multiplies each texel by shade(u, v) (view-independent light). */
    void bakeShading(const std::function<double(double u, double v)>& shade);

    /** Bilinear colour at (u, v) [m], BGR in 0..255; (u, v) clamped to the raster. */
    cv::Vec3f sample(double u, double v) const;
    /** The mean colour over a box `du` x `dv` [m] centred on (u, v): what a camera pixel whose
     * footprint on the surface is that box records (it integrates the light over its area; a
     * point sample of a texture finer than the footprint aliases, and features on the aliased
     * pattern slide over the surface as the camera moves). A box under one texel is widened to
     * one, which is the bilinear sample: magnified, the surface looks as `sample` draws it. */
    cv::Vec3f sampleArea(double u, double v, double du, double dv) const;
    /** Builds what sampleArea needs (the raster's integral image, 12 bytes a texel; kept up to
     * date by bakeShading): only worlds that filter by area pay for it. */
    void prepareAreaSampling();

    const cv::Mat3b& raster() const { return raster_; }
    double pixelsPerMetre() const { return px_per_m_; }

  private:
    /** The integral at a fractional texel corner (x, y): bilinear between the integral's
     * entries, exact for a piecewise-constant raster. */
    cv::Vec3d integralAt(double x, double y) const;

    cv::Mat3b raster_;
    cv::Mat integral_;  ///< (rows + 1) x (cols + 1) x 3: sums of the texels below and left
    double px_per_m_{100};
};

}  // namespace lodestone::sim
