#include "PlyCloud.h"

#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace lodestone::view {

namespace {

constexpr std::size_t kVertexBytes = 3 * sizeof(float) + 3;

/** The header of a binary little-endian PLY with lodestone-slam's vertex layout; the stream
 * is left at the first vertex. */
struct PlyHeader {
    std::size_t vertices{0}, faces{0};
    bool hasFaces{false};
};

PlyHeader readHeader(std::ifstream& in, const std::string& path) {
    const auto fail = [&](const std::string& what) { throw std::runtime_error(path + ": " + what); };
    std::string line;
    PlyHeader h;
    std::vector<std::string> vertexProperties, faceProperties;
    std::vector<std::string>* properties = nullptr;
    bool binary = false;
    if (!std::getline(in, line) || line != "ply") fail("not a PLY file");
    while (std::getline(in, line) && line != "end_header") {
        std::istringstream words(line);
        std::string key;
        words >> key;
        if (key == "format") {
            std::string format;
            words >> format;
            binary = format == "binary_little_endian";
        } else if (key == "element") {
            std::string name;
            words >> name;
            if (name == "vertex") {
                words >> h.vertices;
                properties = &vertexProperties;
            } else if (name == "face") {
                words >> h.faces;
                h.hasFaces = true;
                properties = &faceProperties;
            } else {
                fail("element '" + name + "': only vertices and faces are read");
            }
        } else if (key == "property") {
            if (!properties) fail("a property before any element");
            std::string rest;
            std::getline(words, rest);
            properties->push_back(rest.substr(rest.find_first_not_of(' ')));
        }
    }
    if (line != "end_header") fail("the header has no end_header");
    const std::vector<std::string> expected{"float x",   "float y",     "float z",
                                            "uchar red", "uchar green", "uchar blue"};
    if (!binary || vertexProperties != expected)
        fail("not the layout lodestone-slam writes (binary little-endian x y z float, red green blue uchar)");
    if (h.hasFaces && faceProperties != std::vector<std::string>{"list uchar int vertex_indices"})
        fail("faces not as lodestone-slam writes them (list uchar int vertex_indices)");
    return h;
}

void readVertices(std::ifstream& in, const std::string& path, std::size_t count, std::size_t stride,
                  std::vector<float>& xyz, std::vector<std::uint8_t>& rgb) {
    std::vector<char> vertex(kVertexBytes);
    for (std::size_t i = 0; i < count; ++i) {
        if (!in.read(vertex.data(), static_cast<std::streamsize>(kVertexBytes)))
            throw std::runtime_error(path + ": cut short at vertex " + std::to_string(i) + " of " +
                                     std::to_string(count));
        if (i % stride != 0) continue;
        float p[3];
        std::memcpy(p, vertex.data(), sizeof p);
        xyz.insert(xyz.end(), p, p + 3);
        for (int k = 0; k < 3; ++k) rgb.push_back(static_cast<std::uint8_t>(vertex[12 + k]));
    }
}

}  // namespace

ViewCloud readPlyCloud(const std::string& path, std::size_t maxPoints) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open");
    const PlyHeader h = readHeader(in, path);
    const std::size_t stride = maxPoints == 0 ? h.vertices + 1 : (h.vertices + maxPoints - 1) / maxPoints;
    ViewCloud cloud;
    readVertices(in, path, h.vertices, std::max<std::size_t>(1, stride), cloud.xyz, cloud.rgb);
    return cloud;
}

ViewMesh readPlyMesh(const std::string& path, std::size_t maxTriangles) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open");
    const PlyHeader h = readHeader(in, path);
    if (!h.hasFaces) throw std::runtime_error(path + ": no faces (not a mesh)");
    ViewMesh mesh;
    readVertices(in, path, h.vertices, 1, mesh.xyz, mesh.rgb);
    const std::size_t stride = maxTriangles == 0 ? h.faces + 1 : std::max<std::size_t>(1, (h.faces + maxTriangles - 1) / maxTriangles);
    char face[1 + 3 * sizeof(std::int32_t)];
    for (std::size_t i = 0; i < h.faces; ++i) {
        if (!in.read(face, sizeof face))
            throw std::runtime_error(path + ": cut short at face " + std::to_string(i) + " of " + std::to_string(h.faces));
        if (static_cast<unsigned char>(face[0]) != 3)
            throw std::runtime_error(path + ": face " + std::to_string(i) + " is not a triangle");
        if (i % stride != 0) continue;
        std::int32_t idx[3];
        std::memcpy(idx, face + 1, sizeof idx);
        for (const std::int32_t k : idx)
            if (k < 0 || static_cast<std::size_t>(k) >= h.vertices)
                throw std::runtime_error(path + ": face " + std::to_string(i) + " names vertex " +
                                         std::to_string(k) + " of " + std::to_string(h.vertices));
        mesh.triangles.insert(mesh.triangles.end(), idx, idx + 3);
    }
    return mesh;
}

}  // namespace lodestone::view
