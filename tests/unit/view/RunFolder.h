#pragma once
// A small lodestone-slam output folder written with the project's own writers: two segments
// (a kidnap between nodes 9 and 10), a kept visual closure, a kept magnetic one, a refused one
// and a map.ply; optionally a ground truth 5 cm off in y at every node.
#include <lodestone/graphslam/PoseGraph.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/outputs/ClosureTable.h>
#include <lodestone/outputs/NodeTable.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

namespace lodestone::test {

inline void writeRunFolder(const std::string& dir, bool withTruth, std::size_t plyPoints = 1000) {
    graphslam::Graph graph;
    std::vector<outputs::NodeRow> rows;
    for (std::uint64_t i = 0; i < 20; ++i) {
        // Two laps of a 4 m x 2 m rectangle's long sides: segment 0 along y = 0, 1 along y = 2.
        const double x = 0.4 * double(i % 10), y = i < 10 ? 0.0 : 2.0;
        graph.nodes[i] = mrpt::poses::CPose3D(x, y, 0, 0, 0, 0);
        rows.push_back({static_cast<long long>(i), 100.0 + i, i < 10 ? 0 : 1, i % 3 == 0, 1.0});
        if (i > 0 && i != 10) {
            mrpt::poses::CPose3DPDFGaussianInf step;
            step.mean = graph.nodes[i - 1] - graph.nodes[i];  // (the mean is not drawn)
            graph.insertEdge(i - 1, i, step);
        }
    }
    std::vector<outputs::ClosureRow> closures;
    const auto closure = [&](long long from, long long to, const char* source, bool kept) {
        outputs::ClosureRow r;
        r.fromNode = from;
        r.toNode = to;
        r.source = source;
        r.kept = kept;
        closures.push_back(r);
        if (kept) graph.insertEdge(from, to, mrpt::poses::CPose3DPDFGaussianInf());
    };
    closure(2, 12, "OrbSubmapERD", true);
    closure(5, 15, "MagneticWindowERD", true);
    closure(7, 19, "OrbSubmapERD", false);
    closure(9, 11, "MagneticWindowERD", true);
    closures.back().hypothesis = true;  // (the one that joined segment 1 to the map)
    graph.saveToTextFile(dir + "/graph.graph");
    outputs::writeNodeTable(dir + "/nodes.csv", rows);
    outputs::writeClosureTable(dir + "/closures.csv", closures);
    std::ofstream ply(dir + "/map.ply", std::ios::binary);
    ply << "ply\nformat binary_little_endian 1.0\nelement vertex " << plyPoints
        << "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
           "property uchar green\nproperty uchar blue\nend_header\n";
    for (std::size_t i = 0; i < plyPoints; ++i) {
        const float xyz[3] = {0.004f * float(i), 3.0f, 1.0f};
        const unsigned char rgb[3] = {10, 20, static_cast<unsigned char>(i % 256)};
        ply.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
        ply.write(reinterpret_cast<const char*>(rgb), sizeof rgb);
    }
    if (withTruth) {
        // (and a dense model: two triangles of a 1 m square on the floor)
        std::ofstream mesh(dir + "/mesh.ply", std::ios::binary);
        mesh << "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
        for (const auto& v : {std::array<float, 3>{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}) {
            const unsigned char rgb[3] = {200, 100, 50};
            mesh.write(reinterpret_cast<const char*>(v.data()), 12);
            mesh.write(reinterpret_cast<const char*>(rgb), 3);
        }
        for (const auto& f : {std::array<std::int32_t, 3>{0, 1, 2}, {0, 2, 3}}) {
            mesh.put(3);
            mesh.write(reinterpret_cast<const char*>(f.data()), 12);
        }
    }
    if (withTruth) {
        io::TumTrajectoryWriter truth(dir + "/ground_truth.tum");
        for (std::uint64_t i = 0; i < 20; ++i) {
            const auto& p = graph.nodes.at(i);
            truth.write(100.0 + i, mrpt::poses::CPose3D(p.x(), p.y() + (i == 19 ? 0.5 : 0.0), 0, 0, 0, 0));
        }
    }
}

}  // namespace lodestone::test
