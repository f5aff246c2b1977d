#include "PlyCloud.h"

#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace lodestone::view {

ViewCloud readPlyCloud(const std::string& path, std::size_t maxPoints) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open");
    const auto fail = [&](const std::string& what) { throw std::runtime_error(path + ": " + what); };
    std::string line;
    std::size_t count = 0;
    std::vector<std::string> properties;
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
            if (name != "vertex") fail("element '" + name + "': only vertices are read");
            words >> count;
        } else if (key == "property") {
            std::string type, name;
            words >> type >> name;
            properties.push_back(type + " " + name);
        }
    }
    if (line != "end_header") fail("the header has no end_header");
    const std::vector<std::string> expected{"float x",   "float y",     "float z",
                                            "uchar red", "uchar green", "uchar blue"};
    if (!binary || properties != expected)
        fail("not the layout lodestone-slam writes (binary little-endian x y z float, red green blue uchar)");
    constexpr std::size_t kVertexBytes = 3 * sizeof(float) + 3;
    const std::size_t stride = maxPoints == 0 ? count + 1 : (count + maxPoints - 1) / maxPoints;
    ViewCloud cloud;
    std::vector<char> vertex(kVertexBytes);
    for (std::size_t i = 0; i < count; ++i) {
        if (!in.read(vertex.data(), static_cast<std::streamsize>(kVertexBytes)))
            fail("cut short at vertex " + std::to_string(i) + " of " + std::to_string(count));
        if (i % stride != 0) continue;
        float xyz[3];
        std::memcpy(xyz, vertex.data(), sizeof xyz);
        cloud.xyz.insert(cloud.xyz.end(), xyz, xyz + 3);
        for (int k = 0; k < 3; ++k) cloud.rgb.push_back(static_cast<std::uint8_t>(vertex[12 + k]));
    }
    return cloud;
}

}  // namespace lodestone::view
