#pragma once

#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose3D.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace lodestone::maps {
struct SavedMap;
}

namespace lodestone::view {

/** A node as the view draws it. */
struct ViewNode {
    std::uint64_t id{0};
    mrpt::poses::CPose3D pose;
    int segment{0};       ///< 0 from the start, one more after each kidnap
    bool keyframe{false};
    double timestamp{0};  ///< [s]
    double error{NAN};    ///< [m] against the ground truth (aligned), where one was given
    double field{NAN};    ///< [uT] mean |B| of the magnetometer readings it holds (live view)
};

/** What an edge of the graph stands for. */
enum class EdgeKind {
    Odometry,        ///< from the node decider: wheels, VO, a bridged gap
    Closure,         ///< a loop closer's, kept in the final graph
    RefusedClosure,  ///< a loop closer's, refused by the optimizer (not in the graph)
};

/** The closer name given to the closures that joined a kidnapped segment to the map (a
 * relocation's merge), whichever closer proposed them. */
constexpr const char* kRelocationCloser = "relocation";

struct ViewEdge {
    std::uint64_t from{0}, to{0};
    EdgeKind kind{EdgeKind::Odometry};
    std::string closer;  ///< the loop closer's class name, or kRelocationCloser (closures only)
};

/** Coloured points (the keyframe clouds on the optimized poses), decimated. */
struct ViewCloud {
    std::vector<float> xyz;            ///< x0 y0 z0 x1 ...
    std::vector<std::uint8_t> rgb;     ///< r0 g0 b0 r1 ...
    std::size_t size() const { return xyz.size() / 3; }
};

/** A coloured triangle mesh (the dense model, mesh.ply). */
struct ViewMesh {
    std::vector<float> xyz;                ///< vertices: x0 y0 z0 x1 ...
    std::vector<std::uint8_t> rgb;         ///< their colours
    std::vector<std::int32_t> triangles;   ///< three vertex indices each
    std::size_t size() const { return triangles.size() / 3; }
};

/** Everything a view of a run or a map draws: nodes, edges by kind, the cloud, the truth. */
struct SceneContent {
    std::vector<ViewNode> nodes;  ///< by ID
    std::vector<ViewEdge> edges;
    ViewCloud cloud;
    ViewMesh mesh;  ///< drawn instead of the cloud where there is one
    std::vector<mrpt::math::TPoint3D> truth;  ///< the ground truth's path, aligned to the estimate
    double maxError{NAN};                     ///< [m] over the nodes, NaN without a truth
    bool hasCurrent{false};                   ///< a run going on: where the robot is now
    mrpt::poses::CPose3D current;
    std::vector<std::string> overlay;         ///< status lines drawn over the view
    const ViewNode* node(std::uint64_t id) const;
    int segments() const;  ///< the highest segment + 1
};

/** What to read of a run's folder. */
struct RunReadOptions {
    std::string groundTruth;      ///< a TUM file; "" = the folder's ground_truth.tum if there
    std::size_t maxPoints{200000};  ///< of map.ply, evenly decimated; 0 = no cloud
    std::size_t maxTriangles{2000000};  ///< of mesh.ply, evenly taken; 0 = no mesh
};

/** A lodestone-slam output folder: graph.graph (poses, edges), nodes.csv (segments,
 * keyframes), closures.csv (each closure's closer, kept or refused), map.ply, mesh.ply (the
 * dense model, --mesh) and a ground truth when there is one (each node's error after the TUM
 * benchmark's rigid alignment). Throws std::runtime_error naming the file that is missing or
 * damaged; map.ply, mesh.ply and the truth are optional. */
SceneContent readRunFolder(const std::string& dir, const RunReadOptions& options = {});

/** A saved map (lodestone-slam --map-out): its graph, segments and keyframes; its edges are
 * odometry unless both ends are more than one node apart (a closure, closer unknown). */
SceneContent fromSavedMap(const maps::SavedMap& map);

}  // namespace lodestone::view
