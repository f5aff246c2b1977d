#include <lodestone/sim/World.h>

#include <cmath>

namespace lodestone::sim {

namespace {
constexpr double kMargin = 1.0;  // floor / ceiling beyond the walls [m]
constexpr double kFloorPixelsPerMetre = 100;
}  // namespace

World::World(const Scenario& sc, std::uint64_t seed)
    : ceiling_height_(sc.wallHeight),
      lamp_spacing_(sc.lampSpacing),
      area_filtered_(sc.areaFilteredTextures) {
    Random rng(seed);
    Random textureRng = rng.fork(1), fieldRng = rng.fork(2);
    for (const auto& spec : sc.walls) {
        for (std::size_t i = 0; i + 1 < spec.points.size(); ++i) {
            Wall w{spec.points[i], spec.points[i + 1], sc.wallHeight,
                   static_cast<int>(wall_textures_.size())};
            const double ppm = spec.surface.style == SurfaceStyle::Plain
                                   ? std::min(50.0, sc.texturePixelsPerMetre)  // smooth anyway
                                   : sc.texturePixelsPerMetre;
            SurfaceTexture tex =
                SurfaceTexture::generate(spec.surface, w.length(), w.height, ppm, textureRng);
            const Eigen::Vector2d dir = (w.b - w.a) / w.length();
            tex.bakeShading([&](double u, double v) {
                const Eigen::Vector2d p = w.a + u * dir;
                return lightAt(p.x(), p.y(), v);
            });
            wall_textures_.push_back(std::move(tex));
            wall_styles_.push_back(spec.surface.style);
            plan_.addWall(w);
        }
    }
    floor_origin_ = plan_.minCorner() - Eigen::Vector2d(kMargin, kMargin);
    const Eigen::Vector2d size =
        plan_.maxCorner() - floor_origin_ + Eigen::Vector2d(kMargin, kMargin);
    floor_ =
        SurfaceTexture::generate(sc.floor, size.x(), size.y(), kFloorPixelsPerMetre, textureRng);
    floor_.bakeShading([&](double u, double v) {
        return lightAt(floor_origin_.x() + u, floor_origin_.y() + v, 0.0);
    });
    ceiling_ = SurfaceTexture::generate(sc.ceiling, size.x(), size.y(), 25, textureRng);
    ceiling_.bakeShading([&](double u, double v) {
        // Lamps are bright discs on the ceiling.
        const double s = lamp_spacing_;
        const double x = floor_origin_.x() + u, y = floor_origin_.y() + v;
        const double dx = x - (std::floor(x / s) + 0.5) * s, dy = y - (std::floor(y / s) + 0.5) * s;
        return 0.8 + (dx * dx + dy * dy < 0.04 ? 0.25 : 0.0);
    });
    if (area_filtered_) {
        for (auto& tex : wall_textures_) tex.prepareAreaSampling();
        floor_.prepareAreaSampling();
        ceiling_.prepareAreaSampling();
    }
    buildMagneticField(sc, fieldRng);
}

double World::lightAt(double x, double y, double z) const {
    // The nearest lamp of a square grid at the ceiling; Lambert-ish falloff with distance.
    const double s = lamp_spacing_;
    const double dx = x - (std::floor(x / s) + 0.5) * s, dy = y - (std::floor(y / s) + 0.5) * s;
    const double h = std::max(0.3, ceiling_height_ - z);
    const double d2 = dx * dx + dy * dy + h * h;
    const double reference = ceiling_height_ * ceiling_height_;  // under a lamp, on the floor
    return 0.55 + 0.4 * std::min(1.0, reference / d2);
}

void World::buildMagneticField(const Scenario& sc, Random& rng) {
    const FieldSpec& f = sc.field;
    field_.setEarthField(f.earthMagnitude, f.inclination, f.declination);
    const auto randomDirection = [&]() {
        Eigen::Vector3d v(rng.normal(), rng.normal(), rng.normal());
        return Eigen::Vector3d(v / std::max(1e-9, v.norm()));
    };
    // Rebar and steel studs inside the walls, near the floor and at mid height.
    if (f.wallSpacing > 0) {
        for (const auto& w : plan_.walls()) {
            const int n = std::max(1, static_cast<int>(w.length() / f.wallSpacing));
            for (int i = 0; i < n; ++i) {
                const double s = (i + rng.uniform(0.2, 0.8)) / n;
                const Eigen::Vector2d p = w.a + s * (w.b - w.a);
                const double z =
                    rng.uniform() < 0.5 ? rng.uniform(0.0, 0.3) : rng.uniform(0.8, 1.6);
                field_.addDipole(
                    {{p.x(), p.y(), z},
                     randomDirection() * rng.uniform(f.wallMoment.x(), f.wallMoment.y())});
            }
        }
    }
    // Reinforcement and conduits under the floor.
    const Eigen::Vector2d lo = plan_.minCorner(), hi = plan_.maxCorner();
    const int floorCount = static_cast<int>(f.floorDensity * (hi - lo).prod());
    for (int i = 0; i < floorCount; ++i) {
        const Eigen::Vector3d p(rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y()),
                                -rng.uniform(f.floorDepth.x(), f.floorDepth.y()));
        field_.addDipole(
            {p, randomDirection() * rng.uniform(f.floorMoment.x(), f.floorMoment.y())});
    }
    for (const auto& line : f.lines)
        field_.addLine(line.a, line.b, line.momentPerMetre, line.spacing);
    for (const auto& [p, m] : f.dipoles) field_.addDipole({p, m});
}

}  // namespace lodestone::sim
