#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace lodestone::dense {

/** A coloured triangle mesh. */
struct Mesh {
    std::vector<Eigen::Vector3f> vertices;
    std::vector<std::array<std::uint8_t, 3>> colours;  ///< RGB per vertex
    std::vector<Eigen::Vector3i> triangles;
    bool empty() const { return triangles.empty(); }
};

/** Writes `mesh` as a binary little-endian PLY (float x y z, uchar red green blue per vertex;
 * uchar-counted int vertex indices per face), first to PATH.partial, then renamed. Throws
 * std::runtime_error naming the file when it cannot be written. */
void writeMeshPly(const std::string& path, const Mesh& mesh);

/** Reads a PLY writeMeshPly wrote (binary little-endian, float x y z and uchar r g b per vertex,
 * triangles). Throws std::runtime_error naming the file for one it cannot open, another layout,
 * a file cut short or a face naming a vertex it does not have. */
Mesh readMeshPly(const std::string& path);

}  // namespace lodestone::dense
