#include <lodestone/graphslam/PoseGraph.h>

#include <cmath>

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

OdometryStep odometryStepInto(const Graph& graph, TNodeID id) {
    OdometryStep step;
    if (id == 0) return step;
    const auto e = graph.edges.find({id - 1, id});
    if (e == graph.edges.end()) return step;
    step.length = std::hypot(e->second.mean.x(), e->second.mean.y());
    const mrpt::math::CMatrixDouble66 cov = e->second.cov_inv.inverse_LLt();
    step.varianceXY = cov(0, 0) + cov(1, 1);
    step.varianceYaw = cov(3, 3);
    return step;
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
