// How near a run's dense model lies to the simulated world: mesh.ply's vertices, moved into the
// world by the rigid alignment of the run's trajectory to the simulator's truth (the TUM
// benchmark's), against the world's surfaces (every wall panel, the floor, the ceiling).
// Prints one markdown row: vertices, the median / 95th percentile / mean distance [m], and the
// share within 1 cm and 2 cm.
//   bench_mesh_accuracy SCENARIO.ini RUN_DIR [GROUND_TRUTH.tum]
#include <lodestone/eval/TrajectoryError.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/sim/Scenario.h>
#include <lodestone/sim/World.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

using namespace lodestone;

namespace {

/** The vertices of a binary PLY whose vertices are float x y z and uchar r g b. */
std::vector<Eigen::Vector3d> readVertices(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open");
    std::string line;
    std::size_t count = 0;
    while (std::getline(in, line) && line != "end_header") {
        std::istringstream w(line);
        std::string a, b;
        w >> a >> b;
        if (a == "element" && b == "vertex") w >> count;
    }
    std::vector<Eigen::Vector3d> out;
    char v[15];
    for (std::size_t i = 0; i < count && in.read(v, sizeof v); ++i) {
        float p[3];
        std::memcpy(p, v, sizeof p);
        out.emplace_back(p[0], p[1], p[2]);
    }
    return out;
}

/** Distance from p to the nearest surface of the world [m]. */
double distanceToWorld(const sim::World& world, const Eigen::Vector3d& p) {
    double best = std::min(std::abs(p.z()), std::abs(p.z() - world.ceilingHeight()));
    for (const auto& w : world.floorPlan().walls()) {
        const Eigen::Vector2d ab = w.b - w.a;
        const double s = std::clamp((p.head<2>() - w.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        const double planar = (p.head<2>() - (w.a + s * ab)).norm();
        const double above = p.z() > w.height ? p.z() - w.height : (p.z() < 0 ? -p.z() : 0.0);
        best = std::min(best, std::hypot(planar, above));
    }
    return best;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::cerr << "usage: bench_mesh_accuracy SCENARIO.ini RUN_DIR [GROUND_TRUTH.tum]\n";
        return 2;
    }
    try {
        const sim::Scenario scenario = sim::Scenario::load(argv[1]);
        const sim::World world(scenario, scenario.seed);
        const std::string run = argv[2];
        const auto estimate = io::readTumTrajectory(run + "/trajectory.tum");
        const auto truth = io::readTumTrajectory(argc > 3 ? argv[3] : run + "/ground_truth.tum");
        const auto ate = eval::absoluteTrajectoryError(estimate, truth);
        std::vector<double> d;
        for (const auto& v : readVertices(run + "/mesh.ply")) d.push_back(distanceToWorld(world, ate.alignment * v));
        if (d.empty()) throw std::runtime_error(run + "/mesh.ply: no vertices");
        std::sort(d.begin(), d.end());
        double sum = 0;
        std::size_t within1 = 0, within2 = 0;
        for (const double x : d) sum += x, within1 += x <= 0.01, within2 += x <= 0.02;
        std::printf("| %zu | %.4f | %.4f | %.4f | %.3f | %.3f | %.4f |\n", d.size(), d[d.size() / 2],
                    d[d.size() * 95 / 100], sum / double(d.size()), double(within1) / double(d.size()),
                    double(within2) / double(d.size()), ate.rmse);
    } catch (const std::exception& e) {
        std::cerr << "bench_mesh_accuracy: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
