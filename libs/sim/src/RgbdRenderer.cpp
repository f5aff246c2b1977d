#include <lodestone/sim/RgbdRenderer.h>

#include <cmath>
#include <limits>

namespace lodestone::sim {

RgbdRenderer::RgbdRenderer(const World& world, const CameraSpec& camera, std::uint64_t noiseSeed)
    : world_(world),
      camera_(camera),
      noise_(noiseSeed),
      cos_max_incidence_(std::cos(camera.maxIncidence)) {}

namespace {
/** The extent along a surface's texture axes (u, v) of a pixel's footprint: the ray d (forward
 * component 1) meets the plane of normal n at parameter t, and each pixel step moves the hit by
 * t (step - d (n . step) / (n . d)); the footprint is the box around both moves. */
Eigen::Vector2d footprint(const Eigen::Vector3d& d, double t, const Eigen::Vector3d& n,
                          const Eigen::Vector3d& uAxis, const Eigen::Vector3d& vAxis,
                          const Eigen::Vector3d& column, const Eigen::Vector3d& row) {
    const double nd = n.dot(d);
    Eigen::Vector2d extent(0, 0);
    for (const Eigen::Vector3d* step : {&column, &row}) {
        const Eigen::Vector3d move = t * (*step - d * (n.dot(*step) / nd));
        extent += Eigen::Vector2d(std::abs(move.dot(uAxis)), std::abs(move.dot(vAxis)));
    }
    return extent;
}
}  // namespace

// One pixel: h is the column's horizontal ray direction (forward component 1, so a ray
// parameter is a depth), b the row's vertical slope (up positive).
RgbdRenderer::Surface RgbdRenderer::trace(const Eigen::Vector3d& pos, const Eigen::Vector2d& h,
                                          const std::optional<WallHit>& wall, double b,
                                          const PixelSteps& pixel) const {
    const double hNorm = h.norm();
    const Eigen::Vector3d d(h.x(), h.y(), b);  // (the footprint's ray: area filtering only)
    if (wall) {
        const double z = pos.z() + b * wall->t;
        if (z >= 0 && z <= world_.ceilingHeight()) {
            const Wall& w = world_.floorPlan().walls()[wall->wall];
            const auto& tex = world_.wallTexture(w.surface);
            // Incidence in 3D: the wall normal is horizontal.
            const double cosInc = wall->cosIncidence * hNorm / std::sqrt(hNorm * hNorm + b * b);
            if (!world_.areaFilteredTextures())
                return {wall->t, cosInc, tex.sample(wall->u, z), true};
            const Eigen::Vector2d along = (w.b - w.a) / w.length();
            const Eigen::Vector2d extent =
                footprint(d, wall->t, Eigen::Vector3d(-along.y(), along.x(), 0),
                          Eigen::Vector3d(along.x(), along.y(), 0), Eigen::Vector3d::UnitZ(),
                          pixel.column, pixel.row);
            return {wall->t, cosInc, tex.sampleArea(wall->u, z, extent.x(), extent.y()), true};
        }
    }
    double t;
    const SurfaceTexture* tex;
    if (b < 0) {
        t = pos.z() / -b;
        tex = &world_.floorTexture();
    } else if (b > 0) {
        t = (world_.ceilingHeight() - pos.z()) / b;
        tex = &world_.ceilingTexture();
    } else {
        return {0, 0, cv::Vec3f(0, 0, 0), false};
    }
    const Eigen::Vector2d p = pos.head<2>() + t * h - world_.floorOrigin();
    const double cosInc = std::abs(b) / std::sqrt(hNorm * hNorm + b * b);
    if (!world_.areaFilteredTextures()) return {t, cosInc, tex->sample(p.x(), p.y()), true};
    const Eigen::Vector2d extent =
        footprint(d, t, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
                  Eigen::Vector3d::UnitY(), pixel.column, pixel.row);
    return {t, cosInc, tex->sampleArea(p.x(), p.y(), extent.x(), extent.y()), true};
}

void RgbdRenderer::render(const Eigen::Vector3d& pos, double yaw, Random& rng, cv::Mat3b& rgb,
                          cv::Mat_<uint16_t>& depth) const {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    pose.translation() = pos;
    render(pose, rng, rgb, depth);
}

void RgbdRenderer::render(const Eigen::Isometry3d& pose, Random& rng, cv::Mat3b& rgb,
                          cv::Mat_<uint16_t>& depth) const {
    const int W = camera_.width, H = camera_.height;
    rgb.create(H, W);
    depth.create(H, W);
    const Eigen::Vector3d pos = pose.translation();
    const Eigen::Matrix3d& R = pose.linear();
    // A level camera (turned about the vertical only) keeps a column's horizontal direction
    // down the column: one wall cast per column. Tilted (hand-held), one per pixel.
    const bool level = std::abs(R(2, 0)) < 1e-12 && std::abs(R(2, 1)) < 1e-12;
    const double farT = 1e3;
    const std::size_t rgbNoise = noise_.randomOffset(rng), depthNoise = noise_.randomOffset(rng);
    const float rgbStd = static_cast<float>(camera_.rgbNoise);
    for (int c = 0; c < W; ++c) {
        const double a = (camera_.cx - c) / camera_.fx;  // leftwards slope
        // Ray directions have a forward (optical axis) component of 1: a ray parameter is a depth.
        const Eigen::Vector2d hColumn = (R * Eigen::Vector3d(1, a, 0)).head<2>();
        const auto wallColumn =
            level ? world_.floorPlan().castRay(pos.head<2>(), hColumn, 1e-9, farT) : std::nullopt;
        const PixelSteps pixel{R.col(1) / camera_.fx, R.col(2) / camera_.fy};
        for (int r = 0; r < H; ++r) {
            const double b = (camera_.cy - r) / camera_.fy;  // upwards slope
            Surface s;
            if (level) {
                s = trace(pos, hColumn, wallColumn, b, pixel);
            } else {
                const Eigen::Vector3d d = R * Eigen::Vector3d(1, a, b);
                const Eigen::Vector2d h = d.head<2>();
                s = trace(pos, h, world_.floorPlan().castRay(pos.head<2>(), h, 1e-9, farT), d.z(),
                          pixel);
            }
            const std::size_t i = static_cast<std::size_t>(r) * W + c;
            // Colour: what the surface looks like, plus sensor noise.
            cv::Vec3b& px = rgb(r, c);
            for (int ch = 0; ch < 3; ++ch) {
                px[ch] = cv::saturate_cast<uchar>(s.colour[ch] +
                                                  rgbStd * noise_.at(rgbNoise, 3 * i + ch));
            }
            // Depth: valid only within range and away from grazing angles.
            uint16_t mm = 0;
            if (s.valid && s.depth >= camera_.minRange && s.depth <= camera_.maxRange &&
                s.cosInc >= cos_max_incidence_) {
                const double sigma = camera_.depthNoise * s.depth * s.depth;
                double z = s.depth + sigma * noise_.at(depthNoise, i);
                if (camera_.disparityStep > 0) {
                    // Structured light measures disparity: depth comes in steps of q z^2.
                    const double q = camera_.disparityStep;
                    z = 1.0 / (std::max(1.0, std::round(1.0 / (z * q))) * q);
                }
                mm = static_cast<uint16_t>(std::lround(std::clamp(z, 0.0, 65.0) * 1000.0));
            }
            depth(r, c) = mm;
        }
    }
}

double RgbdRenderer::texturedFraction(const Eigen::Vector3d& pos, double yaw) const {
    const Eigen::Vector2d forward(std::cos(yaw), std::sin(yaw)),
        left(-std::sin(yaw), std::cos(yaw));
    int textured = 0;
    for (int c = 0; c < camera_.width; ++c) {
        const Eigen::Vector2d h = forward + ((camera_.cx - c) / camera_.fx) * left;
        const auto wall = world_.floorPlan().castRay(pos.head<2>(), h, 1e-9, camera_.maxRange);
        if (!wall) continue;
        const int surface = world_.floorPlan().walls()[wall->wall].surface;
        textured += world_.wallStyle(surface) != SurfaceStyle::Plain;
    }
    return static_cast<double>(textured) / camera_.width;
}

double RgbdRenderer::idealDepth(const Eigen::Vector3d& pos, double yaw, int row, int col) const {
    const Eigen::Vector2d forward(std::cos(yaw), std::sin(yaw)),
        left(-std::sin(yaw), std::cos(yaw));
    const Eigen::Vector2d h = forward + ((camera_.cx - col) / camera_.fx) * left;
    const auto wall = world_.floorPlan().castRay(pos.head<2>(), h, 1e-9, 1e3);
    const PixelSteps pixel{Eigen::Vector3d(left.x(), left.y(), 0) / camera_.fx,
                           Eigen::Vector3d::UnitZ() / camera_.fy};
    const Surface s = trace(pos, h, wall, (camera_.cy - row) / camera_.fy, pixel);
    if (!s.valid || s.depth < camera_.minRange || s.depth > camera_.maxRange) {
        return std::numeric_limits<double>::quiet_NaN();
    }
    return s.depth;
}

}  // namespace lodestone::sim
