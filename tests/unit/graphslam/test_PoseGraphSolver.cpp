#include <lodestone/graphslam/gso/PoseGraphSolver.h>
#include <ScaledLoop.h>
#include <SyntheticGraph.h>

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

using namespace lodestone::graphslam;

namespace {

void addClosures(SyntheticGraph& s) {
    for (const auto& lc : s.closures) s.graph.insertEdge(lc.from, lc.to, lc.constraint);
}

SyntheticGraph::Params noiseFree() {
    SyntheticGraph::Params p;
    p.odometrySigmaXY = p.closureSigmaXY = 1e-9;  // drawn noise ~0, claimed 1 cm below
    p.odometrySigmaYaw = p.closureSigmaYaw = 1e-9;
    return p;
}

// Noise-free edges claiming centimetre accuracy, node poses scrambled: the optimum is the truth.
SyntheticGraph scrambledExactGraph(bool threeD) {
    SyntheticGraph s = SyntheticGraph::make(noiseFree());
    for (auto& [ends, c] : s.graph.edges) c.cov_inv = planarInformation(0.01, 0.005);
    for (auto& lc : s.closures) lc.constraint.cov_inv = planarInformation(0.02, 0.01);
    std::mt19937 rng(3);
    std::normal_distribution<double> n(0, 1);
    for (auto& [id, pose] : s.graph.nodes) {
        if (id == 0) continue;
        pose = mrpt::poses::CPose3D(pose.x() + 0.3 * n(rng), pose.y() + 0.3 * n(rng),
                                    threeD ? 0.1 * n(rng) : 0, pose.yaw() + 0.2 * n(rng),
                                    threeD ? 0.05 * n(rng) : 0, threeD ? 0.05 * n(rng) : 0);
    }
    return s;
}

double maxZPitchRoll(const Graph& g) {
    double m = 0;
    for (const auto& [id, p] : g.nodes)
        m = std::max({m, std::abs(p.z()), std::abs(p.pitch()), std::abs(p.roll())});
    return m;
}

}  // namespace

TEST(PoseGraphSolver, PlanarRecoversTheTruthFromScrambledPosesWithExactEdges) {
    SyntheticGraph s = scrambledExactGraph(false);
    ASSERT_GT(positionRmse(s.graph, s.truth), 0.2);
    PoseGraphSolver solver({});
    const auto r = solver.solve(s.graph, s.closures);
    EXPECT_TRUE(r.converged);
    EXPECT_TRUE(r.rejected.empty());
    EXPECT_LT(positionRmse(s.graph, s.truth), 1e-5);
    EXPECT_EQ(r.variableNodes + r.fixedNodes, s.graph.nodes.size());
    EXPECT_EQ(r.fixedNodes, 1u);
}

TEST(PoseGraphSolver, Se3RecoversTheTruthIncludingHeightAndTilt) {
    SyntheticGraph s = scrambledExactGraph(true);
    addClosures(s);
    for (auto& lc : s.closures) lc.constraint = s.graph.edges.find({lc.from, lc.to})->second;
    ASSERT_GT(maxZPitchRoll(s.graph), 0.1);
    PoseGraphSolver::Options o;
    o.planar = false;
    o.rejectionChi2 = 22.46;
    const auto r = PoseGraphSolver(o).solve(s.graph, s.closures);
    EXPECT_TRUE(r.rejected.empty());
    EXPECT_LT(positionRmse(s.graph, s.truth), 1e-4);
    EXPECT_LT(maxZPitchRoll(s.graph), 1e-4);
}

TEST(PoseGraphSolver, PlanarKeepsHeightAndTiltOfTheNodes) {
    SyntheticGraph s = scrambledExactGraph(true);
    const double z7 = s.graph.nodes.at(7).z(), roll7 = s.graph.nodes.at(7).roll();
    PoseGraphSolver({}).solve(s.graph, s.closures);
    EXPECT_DOUBLE_EQ(s.graph.nodes.at(7).z(), z7);
    EXPECT_NEAR(s.graph.nodes.at(7).roll(), roll7, 1e-12);
    EXPECT_LT(positionRmse(s.graph, s.truth), 1e-5);
}

TEST(PoseGraphSolver, AnglesWrapAcrossPlusMinusPi) {
    Graph g;
    g.nodes[0] = mrpt::poses::CPose3D(0, 0, 0, M_PI - 0.01, 0, 0);
    g.nodes[1] = mrpt::poses::CPose3D(0, 0, 0, -M_PI + 0.01, 0, 0);  // 0.02 rad further
    Constraint c;
    c.mean = mrpt::poses::CPose3D(0, 0, 0, 0.02, 0, 0);
    c.cov_inv = planarInformation(0.01, 0.01);
    g.insertEdge(0, 1, c);
    PoseGraphSolver solver({});
    EXPECT_LT(solver.squaredResidual(g, 0, 1, c), 1e-12);
    PoseGraphSolver::Options o;
    o.planar = false;
    EXPECT_LT(PoseGraphSolver(o).squaredResidual(g, 0, 1, c), 1e-12);
    c.mean = mrpt::poses::CPose3D(0, 0, 0, 0.03, 0, 0);  // 1 sigma off
    EXPECT_NEAR(solver.squaredResidual(g, 0, 1, c), 1.0, 1e-9);
}

TEST(PoseGraphSolver, NoisyEdgesBeatDeadReckoningAndNoCorrectClosureIsRejected) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        SyntheticGraph::Params p;
        p.seed = seed;
        SyntheticGraph s = SyntheticGraph::make(p);
        const double deadReckoning = positionRmse(s.graph, s.truth);
        addClosures(s);
        const auto r = PoseGraphSolver({}).solve(s.graph, s.closures);
        const double optimized = positionRmse(s.graph, s.truth);
        SCOPED_TRACE("seed " + std::to_string(seed));
        EXPECT_TRUE(r.rejected.empty()) << "rejected " << r.rejected.size() << ", first chi2 "
                                        << (r.rejected.empty() ? 0 : r.rejected[0].rejectionChi2);
        EXPECT_LT(optimized, 0.5 * deadReckoning) << deadReckoning;
    }
}

TEST(PoseGraphSolver, OneWrongClosureAmongManyIsRejected) {
    SyntheticGraph s = SyntheticGraph::make({});
    const double deadReckoning = positionRmse(s.graph, s.truth);
    // A perceptual alias: a later node claimed 1.5 m and 20 degrees from where it is.
    LoopClosure wrong = s.closures[s.closures.size() / 2];
    wrong.constraint.mean = wrong.constraint.mean + mrpt::poses::CPose3D(1.5, 0.4, 0, 0.35, 0, 0);
    s.closures.push_back(wrong);
    addClosures(s);
    const std::size_t edgesBefore = s.graph.edges.size();
    const auto r = PoseGraphSolver({}).solve(s.graph, s.closures);
    ASSERT_EQ(r.rejected.size(), 1u);
    EXPECT_EQ(r.rejected[0].to, wrong.to);
    EXPECT_EQ(r.rejected[0].constraint.mean, wrong.constraint.mean);
    EXPECT_TRUE(s.closures.back().rejected);
    EXPECT_EQ(s.graph.edges.size(), edgesBefore - 1);
    EXPECT_LT(positionRmse(s.graph, s.truth), 0.5 * deadReckoning);
}

TEST(PoseGraphSolver, AWindowMovesOnlyItsNodes) {
    SyntheticGraph s = scrambledExactGraph(false);
    const Graph before = s.graph;
    std::set<TNodeID> window;
    for (TNodeID id = 40; id < 60; ++id) window.insert(id);
    const auto r = PoseGraphSolver({}).solve(s.graph, s.closures, window);
    EXPECT_EQ(r.variableNodes, window.size());
    EXPECT_EQ(r.fixedNodes, 2u);  // 39 and 60, the window's neighbours
    for (const auto& [id, pose] : s.graph.nodes) {
        if (window.count(id)) continue;
        EXPECT_EQ(pose, before.nodes.at(id)) << id;
    }
    EXPECT_NE(s.graph.nodes.at(50), before.nodes.at(50));
}

TEST(PoseGraphSolver, UnknownRobustLossIsAnError) {
    PoseGraphSolver::Options o;
    o.robustLoss = "tukey";
    EXPECT_THROW(PoseGraphSolver{o}, std::invalid_argument);
}

TEST(PoseGraphSolver, SeveralWrongClosuresAreAllRejectedAndOnlyThem) {
    SyntheticGraph s = SyntheticGraph::make({});
    const std::size_t right = s.closures.size();
    for (std::size_t k : {right / 5, right / 2, 4 * right / 5}) {
        LoopClosure wrong = s.closures[k];
        wrong.constraint.mean = wrong.constraint.mean + mrpt::poses::CPose3D(0.6, -0.8, 0, -0.2, 0, 0);
        wrong.source = "alias";
        s.closures.push_back(wrong);
    }
    addClosures(s);
    const auto r = PoseGraphSolver({}).solve(s.graph, s.closures);
    ASSERT_EQ(r.rejected.size(), 3u);
    for (const auto& lc : r.rejected) {
        EXPECT_EQ(lc.source, "alias");
        EXPECT_GT(lc.rejectionChi2, 16.27);
    }
}

namespace {
/** A level straight walk of `n` nodes 0.5 m apart whose edges each claim a 1 deg pitch (a
 * camera's drift), the nodes placed by chaining them: 10 m on, 1.6 m below. */
Graph driftingChain(int n, double edgePitch) {
    Graph g;
    g.root = 0;
    mrpt::poses::CPose3D pose;
    g.nodes[0] = pose;
    mrpt::math::CMatrixDouble66 info;
    info.setZero();
    for (int k = 0; k < 3; ++k) info(k, k) = 1 / (0.01 * 0.01);
    for (int k = 3; k < 6; ++k) info(k, k) = 1 / std::pow(1.0 * M_PI / 180, 2);
    for (int k = 1; k < n; ++k) {
        Constraint c;
        c.mean = mrpt::poses::CPose3D(0.5, 0, 0, 0, edgePitch, 0);
        c.cov_inv = info;
        g.insertEdge(k - 1, k, c);
        pose = pose + c.mean;
        g.nodes[k] = pose;
    }
    return g;
}
}  // namespace

TEST(PoseGraphSolver, MeasuredUpsLevelAChainWhoseEdgesTilt) {
    const int n = 21;
    const double drift = 1.0 * M_PI / 180;
    Graph g = driftingChain(n, drift);
    ASSERT_LT(g.nodes.at(n - 1).z(), -1.0);
    PoseGraphSolver::Options o;
    o.planar = false;
    std::vector<LoopClosure> none;
    // Every node's up measured level to 0.1 deg (the root's too: the map frame is level).
    AttitudePriors priors;
    for (int k = 0; k < n; ++k) priors.nodes[k] = AttitudePrior{{0, 0, 1}, 0.1 * M_PI / 180};
    Graph plain = g;
    PoseGraphSolver(o).solve(plain, none);
    EXPECT_LT(plain.nodes.at(n - 1).z(), -1.0) << "without them the chain is its own optimum";
    PoseGraphSolver(o).solve(g, none, {}, true, &priors);
    // Each node's pitch pulled to within the priors' reach of level (an edge's 1 deg sigma
    // against a prior's 0.1: they share the drift about 1:100), the end within 0.1 m of level.
    for (const auto& [id, p] : g.nodes) EXPECT_LT(std::abs(p.pitch()), 0.15 * M_PI / 180) << id;
    EXPECT_LT(std::abs(g.nodes.at(n - 1).z()), 0.1);
    EXPECT_LT(std::acos(priors.mapUp.z()), 0.05 * M_PI / 180) << "the map's up solved level";
    // A local window holds the map's up: a tilted one tilts the window's nodes with it.
    Graph w = driftingChain(n, 0);
    AttitudePriors tilted = priors;
    tilted.mapUp = Eigen::Vector3d(std::sin(0.1), 0, std::cos(0.1)).normalized();
    PoseGraphSolver(o).solve(w, none, {10, 11, 12}, false, &tilted);
    EXPECT_NEAR(tilted.mapUp.x(), std::sin(0.1), 1e-12) << "held";
    EXPECT_GT(std::abs(w.nodes.at(11).pitch()), 0.01);
    EXPECT_LT(std::abs(w.nodes.at(5).pitch()), 1e-12) << "outside the window";
}

TEST(PoseGraphSolver, ACarriersHeightStraightensAChainItsUpsAloneLeaveBent) {
    const int n = 21;
    PoseGraphSolver::Options o;
    o.planar = false;
    std::vector<LoopClosure> none;
    // How far the chain bends out of its chord: the level walk's is zero.
    const auto at = [](const mrpt::poses::CPose3D& p) { return Eigen::Vector3d(p.x(), p.y(), p.z()); };
    const auto bend = [n, at](const Graph& g) {
        const Eigen::Vector3d a = at(g.nodes.at(0)), b = at(g.nodes.at(n - 1)), d = (b - a).normalized();
        double worst = 0;
        for (const auto& [id, p] : g.nodes) {
            const Eigen::Vector3d v = at(p) - a;
            worst = std::max(worst, (v - v.dot(d) * d).norm());
        }
        return worst;
    };
    // A carrier held level to 5 deg: each node's up a weak prior against 1 deg edges.
    AttitudePriors ups;
    for (int k = 0; k < n; ++k) ups.nodes[k] = AttitudePrior{{0, 0, 1}, 5 * M_PI / 180};
    Graph upsOnly = driftingChain(n, 1.0 * M_PI / 180);
    PoseGraphSolver(o).solve(upsOnly, none, {}, true, &ups);
    const double bent = bend(upsOnly);
    EXPECT_GT(bent, 0.1) << "the drift stays an arc (0.15 m out of its chord)";
    // The same carrier on one floor: every height held to 5 cm about a common one, solved with
    // the map's up. A straight walk's floor may tilt with its up (nothing here says which is
    // level but the weak ups), so what the heights can judge is the shape: a line, not an arc.
    AttitudePriors floor = ups;
    for (auto& [id, prior] : floor.nodes) prior.heightSigma = 0.05;
    floor.mapHeight = 0.3;  // (a wrong start: solved with the nodes)
    Graph g = driftingChain(n, 1.0 * M_PI / 180);
    PoseGraphSolver(o).solve(g, none, {}, true, &floor);
    EXPECT_LT(bend(g), 0.3 * bent) << "within the heights' 5 cm (measured 0.04 m)";
    double worst = 0;
    for (const auto& [id, p] : g.nodes) {
        worst = std::max(worst, std::abs(floor.mapUp.dot(at(p)) - floor.mapHeight));
    }
    EXPECT_LT(worst, 0.05) << "every node on the solved floor";
    EXPECT_LT(std::abs(floor.mapHeight), 0.05) << "the root is on it";
    // A local window holds the common height, as it holds the up.
    Graph w = driftingChain(n, 0);
    AttitudePriors held = floor;
    held.mapHeight = 0.5;
    PoseGraphSolver(o).solve(w, none, {10, 11, 12}, false, &held);
    EXPECT_EQ(held.mapHeight, 0.5);
    EXPECT_GT(w.nodes.at(11).z(), 0.01) << "the window's nodes drawn towards the held height";
    // Heights with no up anywhere (an accelerometer asked for that never reported): none taken.
    AttitudePriors heightsOnly;
    for (int k = 0; k < n; ++k) heightsOnly.nodes[k] = AttitudePrior{{0, 0, 1}, 0, 0.05};
    Graph h = driftingChain(n, 1.0 * M_PI / 180);
    const Graph before = h;
    PoseGraphSolver(o).solve(h, none, {}, true, &heightsOnly);
    EXPECT_NEAR(h.nodes.at(n - 1).z(), before.nodes.at(n - 1).z(), 1e-6) << "the chain as it was";
}

TEST(PoseGraphSolver, EachNodesMeasuredHeightAboveTheFloorPlacesItThere) {
    // A chain whose edges tilt by 1 deg a step, each node seeing the floor: its up level to
    // 0.3 deg and its height above the floor measured to 1 cm - a hand bobbing 4 cm between
    // nodes, 1.35 m above it. The floor is solved with the nodes (started 0.3 m off), and each
    // node's height above it is its own, not a common one.
    const int n = 21;
    PoseGraphSolver::Options o;
    o.planar = false;
    std::vector<LoopClosure> none;
    const auto bob = [](int k) { return k % 2 == 0 ? 0.0 : 0.04; };
    AttitudePriors seen;
    for (int k = 0; k < n; ++k) {
        AttitudePrior p{{0, 0, 1}, 0.3 * M_PI / 180, 0.01};
        p.height = 1.35 + bob(k);
        seen.nodes[k] = p;
    }
    seen.mapHeight = -1.35 + 0.3;
    // The edges measure each step's rise (the bob) with a 1 deg pitch error each.
    Graph g = driftingChain(n, 1.0 * M_PI / 180);
    for (int k = 1; k < n; ++k) {
        auto& c = g.edges.find({static_cast<TNodeID>(k - 1), static_cast<TNodeID>(k)})->second;
        c.mean = mrpt::poses::CPose3D(0.5, 0, bob(k) - bob(k - 1), 0, 1.0 * M_PI / 180, 0);
    }
    PoseGraphSolver(o).solve(g, none, {}, true, &seen);
    EXPECT_NEAR(seen.mapHeight, -1.35, 0.01) << "the floor under the root (held at 0)";
    for (const auto& [id, p] : g.nodes) {
        const double above = seen.mapUp.dot(Eigen::Vector3d(p.x(), p.y(), p.z())) - seen.mapHeight;
        EXPECT_NEAR(above, 1.35 + bob(static_cast<int>(id)), 0.01) << id;
    }
}

TEST(PoseGraphSolver, WheelScalesAreEstimatedAndTheirArcTakenOutOfALoop) {
    // The wheels 0.3 % apart in scale: 0.75 deg of heading per metre, the same every lap.
    const Eigen::Vector2d scale(0.002, -0.001);
    for (const bool planar : {true, false}) {
        SCOPED_TRACE(planar ? "planar" : "se3");
        PoseGraphSolver::Options o;
        o.planar = planar;
        o.rejectionChi2 = planar ? kChi2Planar999 : kChi2Se3999;
        ScaledLoop plain = scaledLoop(scale);
        ASSERT_GT(worstError(plain.graph, plain.truth), 1.0) << "dead reckoning bends";
        PoseGraphSolver(o).solve(plain.graph, plain.closures, {}, false);
        const double without = worstError(plain.graph, plain.truth);
        EXPECT_GT(without, 0.1) << "tight edges and exact closures disagree";

        ScaledLoop s = scaledLoop(scale);
        s.wheels.sigma = 0.01;
        // A window holds the scales (it sees too little of the run to move them).
        PoseGraphSolver(o).solve(s.graph, s.closures, {100, 101, 102}, false, nullptr, &s.wheels);
        EXPECT_EQ(s.wheels.scale, Eigen::Vector2d::Zero());
        PoseGraphSolver(o).solve(s.graph, s.closures, {}, false, nullptr, &s.wheels);
        // The closures see the heading the wheels' difference makes, not their common scale
        // (both laps shrink alike): the difference to 1e-4, the common part left to its prior.
        EXPECT_NEAR(s.wheels.scale[1] - s.wheels.scale[0], scale[1] - scale[0], 1e-4);
        EXPECT_LT(worstError(s.graph, s.truth), 0.1 * without) << without;
    }
}
