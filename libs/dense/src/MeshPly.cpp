#include <lodestone/dense/Mesh.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
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

Mesh readMeshPly(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open");
    // The header: exactly the layout writeMeshPly writes (comments aside).
    const std::vector<std::string> expected = {
        "ply", "format binary_little_endian 1.0", "element vertex", "property float x", "property float y",
        "property float z", "property uchar red", "property uchar green", "property uchar blue", "element face",
        "property list uchar int vertex_indices", "end_header"};
    std::size_t vertices = 0, faces = 0, k = 0;
    std::string line;
    while (k < expected.size() && std::getline(in, line)) {
        if (line.rfind("comment", 0) == 0) continue;
        std::istringstream words(line);
        std::string a, b;
        words >> a >> b;
        if (expected[k] == "element vertex" || expected[k] == "element face") {
            std::size_t n = 0;
            if (a + " " + b != expected[k] || !(words >> n)) throw std::runtime_error(path + ": not a Lodestone mesh PLY ('" + line + "')");
            (expected[k] == "element vertex" ? vertices : faces) = n;
        } else if (line != expected[k]) {
            throw std::runtime_error(path + ": not a Lodestone mesh PLY ('" + line + "')");
        }
        ++k;
    }
    if (k < expected.size()) throw std::runtime_error(path + ": the header is cut short");
    Mesh mesh;
    mesh.vertices.resize(vertices);
    mesh.colours.resize(vertices);
    char v[15];
    for (std::size_t i = 0; i < vertices; ++i) {
        if (!in.read(v, sizeof v)) throw std::runtime_error(path + ": cut short at vertex " + std::to_string(i));
        std::memcpy(mesh.vertices[i].data(), v, 12);
        std::memcpy(mesh.colours[i].data(), v + 12, 3);
    }
    mesh.triangles.resize(faces);
    char f[13];
    for (std::size_t i = 0; i < faces; ++i) {
        if (!in.read(f, sizeof f)) throw std::runtime_error(path + ": cut short at face " + std::to_string(i));
        std::int32_t idx[3];
        std::memcpy(idx, f + 1, sizeof idx);
        for (const std::int32_t n : idx)
            if (static_cast<unsigned char>(f[0]) != 3 || n < 0 || static_cast<std::size_t>(n) >= vertices)
                throw std::runtime_error(path + ": face " + std::to_string(i) + " is not a triangle of its vertices");
        mesh.triangles[i] = {idx[0], idx[1], idx[2]};
    }
    return mesh;
}

}  // namespace lodestone::dense
