#pragma once

#include <lodestone/sim/FloorPlan.h>
#include <lodestone/sim/MagneticField.h>
#include <lodestone/sim/Scenario.h>
#include <lodestone/sim/SurfaceTexture.h>

#include <vector>

namespace lodestone::sim {

/** The static world of a scenario, built once from the INI and a seed: walls with their lit
 * textures, floor and ceiling, and the magnetic field. Same scenario + seed, same world. */
class World {
  public:
    World(const Scenario& scenario, std::uint64_t seed);

    const FloorPlan& floorPlan() const { return plan_; }
    const SurfaceTexture& wallTexture(int surface) const { return wall_textures_[surface]; }
    SurfaceStyle wallStyle(int surface) const { return wall_styles_[surface]; }
    const SurfaceTexture& floorTexture() const { return floor_; }
    const SurfaceTexture& ceilingTexture() const { return ceiling_; }
    /** World (x, y) of the floor and ceiling textures' (u, v) = (0, 0) [m]. */
    const Eigen::Vector2d& floorOrigin() const { return floor_origin_; }
    double ceilingHeight() const { return ceiling_height_; }
    /** Scenario::areaFilteredTextures: a pixel averages the texture over its footprint. */
    bool areaFilteredTextures() const { return area_filtered_; }
    const MagneticField& field() const { return field_; }

    /** View-independent light factor at a world point (ceiling lamps on a grid). */
    double lightAt(double x, double y, double z) const;

  private:
    void buildMagneticField(const Scenario& scenario, Random& rng);

    FloorPlan plan_;
    std::vector<SurfaceTexture> wall_textures_;  // one per wall segment (Wall::surface)
    std::vector<SurfaceStyle> wall_styles_;
    SurfaceTexture floor_, ceiling_;
    Eigen::Vector2d floor_origin_;
    double ceiling_height_;
    double lamp_spacing_;
    bool area_filtered_;
    MagneticField field_;
};

}  // namespace lodestone::sim
