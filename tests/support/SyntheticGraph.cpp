#include <SyntheticGraph.h>

#include <cmath>
#include <random>

namespace lodestone::graphslam {

mrpt::math::CMatrixDouble66 planarInformation(double sigmaXY, double sigmaYaw) {
    mrpt::math::CMatrixDouble66 info;
    info.setZero();
    info(0, 0) = info(1, 1) = 1 / (sigmaXY * sigmaXY);
    info(3, 3) = 1 / (sigmaYaw * sigmaYaw);
    info(2, 2) = info(4, 4) = info(5, 5) = kPlanarStiffness;
    return info;
}

SyntheticGraph SyntheticGraph::make(const Params& p) {
    SyntheticGraph s;
    std::mt19937_64 rng(p.seed);
    std::normal_distribution<double> unit(0.0, 1.0);
    const int perSide = static_cast<int>(std::lround(p.side / p.step));
    s.nodesPerLap = static_cast<std::size_t>(4 * perSide);
    // Truth: along each side, then turn 90 degrees in place at the corner node.
    mrpt::poses::CPose3D pose;
    for (int lap = 0; lap < p.laps; ++lap) {
        for (int side = 0; side < 4; ++side) {
            for (int k = 0; k < perSide; ++k) {
                s.truth.push_back(pose);
                const bool corner = k == perSide - 1;
                pose = pose + mrpt::poses::CPose3D(p.step, 0, 0, corner ? M_PI / 2 : 0, 0, 0);
            }
        }
    }
    s.truth.push_back(pose);
    const auto noisy = [&](const mrpt::poses::CPose3D& z, double sxy, double syaw) {
        return mrpt::poses::CPose3D(z.x() + sxy * unit(rng), z.y() + sxy * unit(rng), 0,
                                    z.yaw() + syaw * unit(rng), 0, 0);
    };
    s.graph.root = 0;
    s.graph.nodes[0] = mrpt::poses::CPose3D();
    for (std::size_t i = 0; i + 1 < s.truth.size(); ++i) {
        Constraint c;
        c.mean = noisy(s.truth[i + 1] - s.truth[i], p.odometrySigmaXY, p.odometrySigmaYaw);
        c.cov_inv = planarInformation(p.odometrySigmaXY, p.odometrySigmaYaw);
        s.graph.insertEdge(i, i + 1, c);
        s.graph.nodes[i + 1] = s.graph.nodes[i] + c.mean;
    }
    if (p.closureEvery > 0) {
        for (std::size_t j = s.nodesPerLap; j < s.truth.size(); j += p.closureEvery) {
            const std::size_t i = p.closeToPreviousLap ? j - s.nodesPerLap : j % s.nodesPerLap;
            LoopClosure lc;
            lc.from = i;
            lc.to = j;
            lc.constraint.mean =
                noisy(s.truth[j] - s.truth[i], p.closureSigmaXY, p.closureSigmaYaw);
            lc.constraint.cov_inv = planarInformation(p.closureSigmaXY, p.closureSigmaYaw);
            lc.source = "synthetic";
            s.closures.push_back(lc);
        }
    }
    return s;
}

double positionRmse(const Graph& graph, const std::vector<mrpt::poses::CPose3D>& truth) {
    const auto& n0 = graph.nodes.at(0);
    double sq = 0;
    for (std::size_t i = 0; i < truth.size(); ++i) {
        const auto e = graph.nodes.at(i) - n0;
        const auto g = truth[i] - truth[0];
        sq += std::pow(e.x() - g.x(), 2) + std::pow(e.y() - g.y(), 2);
    }
    return std::sqrt(sq / truth.size());
}

}  // namespace lodestone::graphslam
