#pragma once

#include <lodestone/sim/Scenario.h>

namespace lodestone::test {

/** A 10 m x 6 m room, x in [-2, 8], y in [-3, 3]: the wall at x = 8 in front of a robot at the
 * origin heading +x is `frontSurface`, the others plain. */
inline sim::Scenario boxScenario(const std::string& frontSurface = "posters") {
    sim::Scenario sc;
    sc.name = "box";
    sc.source = "box (test)";
    sc.wallHeight = 2.5;
    sc.texturePixelsPerMetre = 200;
    sc.floor = sim::SurfaceSpec::parse("plain");
    sc.ceiling = sim::SurfaceSpec::parse("plain");
    const auto wall = [&](const std::string& surface, std::vector<Eigen::Vector2d> pts) {
        sim::WallSpec w;
        w.name = "wall";
        w.surface = sim::SurfaceSpec::parse(surface);
        w.points = std::move(pts);
        sc.walls.push_back(w);
    };
    wall(frontSurface, {{8, -3}, {8, 3}});
    wall("plain", {{8, 3}, {-2, 3}, {-2, -3}, {8, -3}});
    sc.motion.waypoints = {{0, 0}, {4, 0}};
    sc.motion.laps = 1;
    sc.field.wallSpacing = 0;
    sc.field.floorDensity = 0;
    sc.magnetometers.push_back({"MAG", 100, {0, 0.1, 0.3, 0}, 0.0, {0, 0, 0}});
    return sc;
}

}  // namespace lodestone::test
