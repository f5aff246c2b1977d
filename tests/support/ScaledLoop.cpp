#include <ScaledLoop.h>
#include <lodestone/odometry/DiffDriveOdometry.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>

namespace lodestone::graphslam {

ScaledLoop scaledLoop(const Eigen::Vector2d& scale) {
    using lodestone::odometry::DiffDriveOdometry;
    DiffDriveOdometry::Params p;
    p.wheelNoise = 1e-6;
    // Each node's true wheel travels: 0.1 m straight, or a quarter turn in place in 5 steps.
    std::vector<std::pair<double, double>> travel;
    const double turn = M_PI / 2 * p.wheelBase / 2 / 5;
    for (int lap = 0; lap < 2; ++lap) {
        for (const int side : {60, 30, 60, 30}) {
            for (int k = 0; k < side; ++k) travel.emplace_back(0.1, 0.1);
            for (int k = 0; k < 5; ++k) travel.emplace_back(-turn, turn);
        }
    }
    ScaledLoop s;
    s.graph.root = s.truth.root = 0;
    mrpt::poses::CPose3D measured, real;
    s.graph.nodes[0] = measured;
    s.truth.nodes[0] = real;
    for (std::size_t k = 0; k < travel.size(); ++k) {
        const auto [l, r] = travel[k];
        const double ml = l / (1 + scale[0]), mr = r / (1 + scale[1]);  // what they measured
        const auto step = DiffDriveOdometry::stepFromOrigin(ml, mr, p);
        Constraint c;
        c.mean = mrpt::poses::CPose3D(step.mean.x(), step.mean.y(), 0, step.mean.phi(), 0, 0);
        c.cov_inv.setIdentity();
        const Eigen::Matrix3d info =
            (step.cov.asEigen() + 1e-8 * Eigen::Matrix3d::Identity()).inverse();
        const int at[3] = {0, 1, 3};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) c.cov_inv(at[i], at[j]) = info(i, j);
        const auto from = static_cast<TNodeID>(k), to = from + 1;
        s.graph.insertEdge(from, to, c);
        s.wheels.edges[{from, to}] = DiffDriveOdometry::scaleJacobian(ml, mr, p);
        measured = measured + c.mean;
        const auto truthStep = DiffDriveOdometry::stepFromOrigin(l, r, p).mean;
        real = real + mrpt::poses::CPose3D(truthStep.x(), truthStep.y(), 0, truthStep.phi(), 0, 0);
        s.graph.nodes[to] = measured;
        s.truth.nodes[to] = real;
    }
    const auto lap = static_cast<TNodeID>(travel.size() / 2);
    for (const TNodeID to : {lap, 2 * lap}) {
        LoopClosure lc;
        lc.from = to - lap;
        lc.to = to;
        lc.source = "test";
        lc.constraint.mean = s.truth.nodes.at(to) - s.truth.nodes.at(lc.from);
        lc.constraint.cov_inv.setIdentity();
        for (int k : {0, 1}) lc.constraint.cov_inv(k, k) = 1e4;
        lc.constraint.cov_inv(3, 3) = 1 / std::pow(0.5 * M_PI / 180, 2);
        s.graph.insertEdge(lc.from, lc.to, lc.constraint);
        s.closures.push_back(lc);
    }
    return s;
}

double worstError(const Graph& g, const Graph& truth) {
    double worst = 0;
    for (const auto& [id, p] : g.nodes) {
        const auto& t = truth.nodes.at(id);
        worst = std::max(worst, std::hypot(p.x() - t.x(), p.y() - t.y()));
    }
    return worst;
}

}  // namespace lodestone::graphslam
