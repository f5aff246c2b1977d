#include <lodestone/dense/Mesh.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace lodestone::dense {

void writeMeshPly(const std::string& path, const Mesh& mesh) {
    const std::string partial = path + ".partial";
    {
        std::ofstream out(partial, std::ios::binary | std::ios::trunc);
        if (!out) throw std::runtime_error(path + ": cannot be written");
        out << "ply\nformat binary_little_endian 1.0\ncomment Lodestone dense model (TSDF, marching cubes)\n"
            << "element vertex " << mesh.vertices.size()
            << "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
               "property uchar green\nproperty uchar blue\nelement face "
            << mesh.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
        for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
            out.write(reinterpret_cast<const char*>(mesh.vertices[i].data()), 3 * sizeof(float));
            out.write(reinterpret_cast<const char*>(mesh.colours[i].data()), 3);
        }
        for (const auto& t : mesh.triangles) {
            const unsigned char three = 3;
            const std::int32_t idx[3] = {t.x(), t.y(), t.z()};
            out.put(static_cast<char>(three));
            out.write(reinterpret_cast<const char*>(idx), sizeof idx);
        }
        if (!out) throw std::runtime_error(path + ": write failed");
    }
    std::error_code ec;
    std::filesystem::rename(partial, path, ec);
    if (ec) throw std::runtime_error(path + ": cannot be written (" + ec.message() + ")");
}

}  // namespace lodestone::dense
