// How near a run's dense model lies to the simulated world: mesh.ply's vertices, moved into the
// world by the rigid alignment of the run's trajectory to the simulator's truth (the TUM
// benchmark's), against the world's surfaces (every wall panel, the floor, the ceiling); and
// how much of what the camera saw the mesh holds: the world's surface points seen within 3 m
// from the true camera pose every 0.5 s of the run (rendered noise-free by the simulator's
// renderer, every 4th pixel each way), the share with a mesh vertex within 2 cm. The robot's
// camera (its mount on the true robot pose) or, with --handheld, the camera's own true pose.
// And how much of that seen surface the mesh shows twice (a wall doubled by a trajectory that
// disagrees with itself where it passes again): two layers of vertices along its normal.
// Prints one markdown row: vertices, the median / 95th percentile / mean distance [m], the
// share within 1 cm and 2 cm, the trajectory's ATE, the completeness and the doubled share.
//   bench_mesh_accuracy SCENARIO.ini RUN_DIR [GROUND_TRUTH.tum] [--handheld]
#include <lodestone/dense/Mesh.h>
#include <lodestone/eval/TrajectoryError.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/outputs/NodeTable.h>
#include <lodestone/sim/RgbdRenderer.h>
#include <lodestone/sim/Scenario.h>
#include <lodestone/sim/World.h>

#include <nanoflann.hpp>

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

/** The normal of the world's surface nearest to p (floor, ceiling or a wall's face). */
Eigen::Vector3d normalAt(const sim::World& world, const Eigen::Vector3d& p) {
    double best = std::abs(p.z());
    Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
    if (std::abs(p.z() - world.ceilingHeight()) < best) best = std::abs(p.z() - world.ceilingHeight());
    for (const auto& w : world.floorPlan().walls()) {
        const Eigen::Vector2d ab = w.b - w.a;
        const double s = std::clamp((p.head<2>() - w.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        const double planar = (p.head<2>() - (w.a + s * ab)).norm();
        if (planar < best && p.z() <= w.height) {
            best = planar;
            n = Eigen::Vector3d(-ab.y(), ab.x(), 0).normalized();
        }
    }
    return n;
}

/** nanoflann's view of the mesh's vertices. */
struct Vertices {
    const std::vector<Eigen::Vector3d>* v;
    std::size_t kdtree_get_point_count() const { return v->size(); }
    double kdtree_get_pt(std::size_t i, std::size_t d) const { return (*v)[i][static_cast<Eigen::Index>(d)]; }
    template <class BBox>
    bool kdtree_get_bbox(BBox&) const {
        return false;
    }
};
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Vertices>, Vertices, 3>;

/** What the mesh makes of the world's surface the camera saw within 3 m (from its true pose
 * every 0.5 s of the run). */
struct Coverage {
    double held{0};     ///< the share with a mesh vertex within 2 cm
    double doubled{0};  ///< the share the mesh shows twice: vertices within 1.5 cm of the point's
                        ///< normal line and 8 cm of the point, in two layers more than 2 cm apart
};

/** Two layers along the normal: the vertices near p's normal line, sorted by their offset along
 * it, part at a gap over 2 cm with at least two vertices on each side. */
bool twoLayers(const Tree& tree, const std::vector<Eigen::Vector3d>& mesh, const Eigen::Vector3d& p,
               const Eigen::Vector3d& n) {
    std::vector<std::pair<unsigned int, double>> hits;
    tree.radiusSearch(p.data(), 0.08 * 0.08, hits, nanoflann::SearchParams(32, 0, false));
    std::vector<double> along;
    for (const auto& h : hits) {
        const Eigen::Vector3d d = mesh[h.first] - p;
        const double o = d.dot(n);
        if ((d - o * n).norm() <= 0.015) along.push_back(o);
    }
    std::sort(along.begin(), along.end());
    for (std::size_t i = 2; i + 1 < along.size(); ++i)
        if (along[i] - along[i - 1] > 0.02) return true;
    return false;
}

Coverage coverage(const sim::Scenario& scenario, const sim::World& world, const std::string& run,
                  const std::vector<io::TumPose>& truth, const std::vector<Eigen::Vector3d>& mesh, bool handheld) {
    Vertices vertices{&mesh};
    Tree tree(3, vertices, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    tree.buildIndex();
    sim::CameraSpec camera = scenario.camera;
    camera.depthNoise = 0;
    const sim::RgbdRenderer renderer(world, camera, 1);
    sim::Random rng(1);
    const auto& m = camera.pose;
    // (a hand-held camera's truth is the camera's own pose)
    const Eigen::Isometry3d mount = handheld ? Eigen::Isometry3d::Identity()
                                             : Eigen::Isometry3d(Eigen::Translation3d(m.x, m.y, m.z) *
                                                                 Eigen::AngleAxisd(m.yaw, Eigen::Vector3d::UnitZ()));
    std::size_t seen = 0, held = 0, doubled = 0, layered = 0;
    const auto nodes = outputs::readNodeTable(run + "/nodes.csv");
    if (nodes.empty()) return {};
    double next = nodes.front().timestamp;
    for (const auto& truthPose : truth) {
        if (truthPose.timestamp < next || truthPose.timestamp > nodes.back().timestamp) continue;
        next = truthPose.timestamp + 0.5;
        const io::TumPose* robot = &truthPose;
        const auto& rp = robot->pose;
        const Eigen::Isometry3d T = Eigen::Translation3d(rp.x(), rp.y(), rp.z()) *
                                    Eigen::AngleAxisd(rp.yaw(), Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(rp.pitch(), Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(rp.roll(), Eigen::Vector3d::UnitX());
        const Eigen::Isometry3d cam = T * mount;
        cv::Mat3b rgb;
        cv::Mat_<std::uint16_t> depth;
        renderer.render(cam, rng, rgb, depth);
        for (int v = 0; v < depth.rows; v += 4) {
            for (int u = 0; u < depth.cols; u += 4) {
                const double z = depth(v, u) * 1e-3;
                if (!(z > 0) || z > 3.0) continue;
                // (the optical ray in MRPT's depth frame: x forward, y left, z up)
                const Eigen::Vector3d p = cam * Eigen::Vector3d(z, -(u - camera.cx) / camera.fx * z,
                                                                -(v - camera.cy) / camera.fy * z);
                std::size_t index = 0;
                double d2 = 0;
                nanoflann::KNNResultSet<double> result(1);
                result.init(&index, &d2);
                tree.findNeighbors(result, p.data(), nanoflann::SearchParams());
                ++seen;
                held += d2 <= 0.02 * 0.02;
                // (every 4th sample each way again for the layers: a radius search a point)
                if ((u / 4) % 4 == 0 && (v / 4) % 4 == 0) {
                    ++layered;
                    doubled += twoLayers(tree, mesh, p, normalAt(world, p));
                }
            }
        }
    }
    std::fprintf(stderr, "completeness: %zu of %zu seen points held; %zu of %zu doubled\n", held, seen, doubled,
                 layered);
    if (seen == 0) return {};
    return {double(held) / double(seen), layered ? double(doubled) / double(layered) : 0.0};
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    const auto flag = std::find(args.begin(), args.end(), "--handheld");
    const bool handheld = flag != args.end();
    if (handheld) args.erase(flag);
    if (args.size() < 2) {
        std::cerr << "usage: bench_mesh_accuracy SCENARIO.ini RUN_DIR [GROUND_TRUTH.tum] [--handheld]\n";
        return 2;
    }
    try {
        const sim::Scenario scenario = sim::Scenario::load(args[0]);
        const sim::World world(scenario, scenario.seed);
        const std::string run = args[1];
        const auto estimate = io::readTumTrajectory(run + "/trajectory.tum");
        const auto truth = io::readTumTrajectory(args.size() > 2 ? args[2] : run + "/ground_truth.tum");
        const auto ate = eval::absoluteTrajectoryError(estimate, truth);
        std::vector<double> d;
        std::vector<Eigen::Vector3d> inWorld;
        for (const auto& v : dense::readMeshPly(run + "/mesh.ply").vertices) {
            inWorld.push_back(ate.alignment * v.cast<double>());
            d.push_back(distanceToWorld(world, inWorld.back()));
        }
        if (d.empty()) throw std::runtime_error(run + "/mesh.ply: no vertices");
        std::sort(d.begin(), d.end());
        double sum = 0;
        std::size_t within1 = 0, within2 = 0;
        for (const double x : d) sum += x, within1 += x <= 0.01, within2 += x <= 0.02;
        const Coverage cover = coverage(scenario, world, run, truth, inWorld, handheld);
        std::printf("| %zu | %.4f | %.4f | %.4f | %.3f | %.3f | %.4f | %.3f | %.4f |\n", d.size(), d[d.size() / 2],
                    d[d.size() * 95 / 100], sum / double(d.size()), double(within1) / double(d.size()),
                    double(within2) / double(d.size()), ate.rmse, cover.held, cover.doubled);
    } catch (const std::exception& e) {
        std::cerr << "bench_mesh_accuracy: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
