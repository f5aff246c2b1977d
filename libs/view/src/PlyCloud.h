#pragma once

#include <lodestone/view/SceneContent.h>

#include <string>

namespace lodestone::view {

/** The points of a PLY as lodestone-slam writes map.ply (binary little-endian; float x y z,
 * uchar red green blue per vertex), at most `maxPoints` of them, evenly taken. Throws
 * std::runtime_error naming the file for any other layout or a file cut short. */
ViewCloud readPlyCloud(const std::string& path, std::size_t maxPoints);

/** A mesh as lodestone-slam --mesh writes mesh.ply (those vertices, then faces of a uchar
 * count 3 and int indices), at most `maxTriangles` triangles, evenly taken. Throws
 * std::runtime_error naming the file for another layout, a file cut short or an index out of
 * range. */
ViewMesh readPlyMesh(const std::string& path, std::size_t maxTriangles);

}  // namespace lodestone::view
