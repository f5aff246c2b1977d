// A saved map the size of an hour's run, for lodestone-view's first picture: NODES nodes on a
// lawnmower path over a 60 m x 40 m floor (a node every 0.1 m, a keyframe every third), the
// chain's edges and a closure wherever the path passes within 0.3 m of a node 200 or more
// before it, written as lodestone-slam --map-out writes a map.
//   bench_view_map OUT_DIR [NODES]   (default 35000)
#include <lodestone/maps/SavedMap.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace lodestone;

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_view_map OUT_DIR [NODES]\n");
        return 2;
    }
    const std::size_t count = argc > 2 ? std::stoul(argv[2]) : 35000;
    maps::SavedMap map;
    map.manifest.createdBy = "bench_view_map";
    // Rows 40 m long, 2 m apart, back and forth; the path starts over when the floor is full
    // (later passes 0.2 m aside: the closures' revisits).
    const double rowLength = 40, rowGap = 2, step = 0.1;
    const std::size_t perRow = static_cast<std::size_t>(rowLength / step);
    const std::size_t rows = 30;
    for (std::size_t i = 0; i < count; ++i) {
        const std::size_t pass = i / (perRow * rows), row = (i / perRow) % rows, along = i % perRow;
        const double x = row % 2 == 0 ? along * step : rowLength - along * step;
        const double y = row * rowGap + 0.2 * double(pass % 2);
        const double yaw = row % 2 == 0 ? 0 : M_PI;
        map.graph.nodes[i] = mrpt::poses::CPose3D(x, y, 0, yaw, 0, 0);
        graphslam::NodeRecord r;
        r.timestamp = 0.1 * double(i);
        r.keyframe = i % 3 == 0;
        map.nodes.push_back(r);
        map.sessions.push_back(0);
        if (i == 0) continue;
        mrpt::poses::CPose3DPDFGaussianInf edge;
        edge.mean = map.graph.nodes[i] - map.graph.nodes[i - 1];
        edge.cov_inv.setIdentity();
        edge.cov_inv *= 1e4;
        map.graph.insertEdge(i - 1, i, edge);
        // One closure per revisited metre.
        if (pass > 0 && along % 10 == 0) {
            const std::size_t earlier = i - perRow * rows;
            mrpt::poses::CPose3DPDFGaussianInf closure;
            closure.mean = map.graph.nodes[i] - map.graph.nodes[earlier];
            closure.cov_inv.setIdentity();
            map.graph.insertEdge(earlier, i, closure);
        }
    }
    maps::writeMap(map, argv[1]);
    std::printf("%zu nodes, %zu edges -> %s\n", map.graph.nodes.size(), map.graph.edges.size(), argv[1]);
    return 0;
}
