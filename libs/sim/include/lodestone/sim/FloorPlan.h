#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace lodestone::sim {

/** One vertical wall panel: a 2D segment extruded from the floor to `height`. */
struct Wall {
    Eigen::Vector2d a, b;  ///< end points on the floor [m]
    double height{2.6};    ///< [m]
    int surface{0};        ///< index of its SurfaceTexture in the world
    double length() const { return (b - a).norm(); }
};

/** Where a horizontal ray meets the walls. */
struct WallHit {
    double t;             ///< ray parameter: hit = origin + t * direction
    int wall;             ///< index into FloorPlan::walls()
    double u;             ///< distance along the wall from its end a [m]
    double cosIncidence;  ///< |cos| of the angle between the ray and the wall normal
};

/** The walls of the world, as 2D segments, with the geometric queries the simulator needs. */
class FloorPlan {
  public:
    void addWall(const Wall& wall);
    const std::vector<Wall>& walls() const { return walls_; }

    /** Nearest wall hit along origin + t * direction, t in (tMin, tMax]. */
    std::optional<WallHit> castRay(const Eigen::Vector2d& origin, const Eigen::Vector2d& direction,
                                   double tMin, double tMax) const;

    /** Distance from `p` to the nearest wall [m] (infinity without walls). */
    double clearance(const Eigen::Vector2d& p) const;

    /** True if the straight move a -> b passes closer than `clearance` to a wall (or through
     * one). */
    bool blocks(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double clearance) const;

    /** Axis-aligned bounds of all walls: min (x, y) and max (x, y) [m]. */
    Eigen::Vector2d minCorner() const;
    Eigen::Vector2d maxCorner() const;

  private:
    std::vector<Wall> walls_;
};

/** Distance between segments p0-p1 and q0-q1 in the plane (0 if they cross). */
double segmentDistance(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1,
                       const Eigen::Vector2d& q0, const Eigen::Vector2d& q1);

}  // namespace lodestone::sim
