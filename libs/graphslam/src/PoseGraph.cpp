#include <lodestone/graphslam/PoseGraph.h>

namespace lodestone::graphslam {

Constraint planarConstraint(const mrpt::poses::CPosePDFGaussian& motion) {
    constexpr double kVarianceFloor = 1e-10;  // [m^2, rad^2]
    Constraint c;
    c.mean = mrpt::poses::CPose3D(motion.mean.x(), motion.mean.y(), 0, motion.mean.phi(), 0, 0);
    mrpt::math::CMatrixDouble33 cov = motion.cov;
    for (int k = 0; k < 3; ++k) cov(k, k) += kVarianceFloor;
    const mrpt::math::CMatrixDouble33 info = cov.inverse_LLt();
    constexpr int kAt[3] = {0, 1, 3};  // x, y, yaw in MRPT's 6D order
    c.cov_inv.setZero();
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) c.cov_inv(kAt[r], kAt[k]) = info(r, k);
    c.cov_inv(2, 2) = c.cov_inv(4, 4) = c.cov_inv(5, 5) = kPlanarStiffness;
    return c;
}

bool eraseEdge(Graph& graph, TNodeID from, TNodeID to, const Constraint& c) {
    const auto range = graph.edges.equal_range({from, to});
    for (auto it = range.first; it != range.second; ++it) {
        if (it->second.mean == c.mean) {
            graph.edges.erase(it);
            return true;
        }
    }
    return false;
}

bool hasEdge(const Graph& graph, TNodeID from, TNodeID to, const Constraint& c) {
    const auto range = graph.edges.equal_range({from, to});
    for (auto it = range.first; it != range.second; ++it) {
        if (it->second.mean == c.mean) return true;
    }
    return false;
}

}  // namespace lodestone::graphslam
