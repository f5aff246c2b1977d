#include <ceres/autodiff_cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <ceres/sphere_manifold.h>
#include <lodestone/graphslam/gso/PoseGraphSolver.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <unordered_set>

#include "RelativePoseCosts.h"

namespace lodestone::graphslam {

namespace {

using detail::informationSqrt;

/** One node's variables in both parameterizations (only one is used per solve). */
struct NodeState {
    double planar[3];  // x, y, yaw
    double t[3];
    double q[4];  // x, y, z, w
};

NodeState stateOf(const mrpt::poses::CPose3D& p) {
    NodeState s{};
    s.planar[0] = p.x();
    s.planar[1] = p.y();
    s.planar[2] = p.yaw();
    s.t[0] = p.x();
    s.t[1] = p.y();
    s.t[2] = p.z();
    const Eigen::Quaterniond q(p.getRotationMatrix().asEigen());
    s.q[0] = q.x();
    s.q[1] = q.y();
    s.q[2] = q.z();
    s.q[3] = q.w();
    return s;
}

mrpt::poses::CPose3D poseOf(const NodeState& s, const mrpt::poses::CPose3D& before, bool planar) {
    if (planar) {
        return mrpt::poses::CPose3D(s.planar[0], s.planar[1], before.z(), s.planar[2],
                                    before.pitch(), before.roll());
    }
    const Eigen::Quaterniond q(s.q[3], s.q[0], s.q[1], s.q[2]);
    mrpt::math::CMatrixDouble33 R(q.normalized().toRotationMatrix());
    mrpt::math::CVectorFixedDouble<3> t;
    for (int k = 0; k < 3; ++k) t[k] = s.t[k];
    return mrpt::poses::CPose3D(R, t);
}

// MRPT orders a 3D pose's covariance x, y, z, yaw, pitch, roll; the SE(3) error is ordered
// x, y, z, then rotation about x (roll), y (pitch), z (yaw).
constexpr int kSe3FromMrpt[6] = {0, 1, 2, 5, 4, 3};
constexpr int kPlanarFromMrpt[3] = {0, 1, 3};

ceres::CostFunction* makeCost(const Constraint& c, bool planar,
                              const Eigen::Matrix<double, 3, 2>* scaleJacobian = nullptr) {
    const auto& info = c.cov_inv;
    if (planar) {
        Eigen::Matrix3d I;
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k) I(r, k) = info(kPlanarFromMrpt[r], kPlanarFromMrpt[k]);
        const Eigen::Vector3d z(c.mean.x(), c.mean.y(), c.mean.yaw());
        if (scaleJacobian) {
            return new ceres::AutoDiffCostFunction<detail::ScaledPlanarRelativePoseCost, 3, 3, 3,
                                                   2>(new detail::ScaledPlanarRelativePoseCost(
                z, *scaleJacobian, informationSqrt<3>(I)));
        }
        return new ceres::AutoDiffCostFunction<detail::PlanarRelativePoseCost, 3, 3, 3>(
            new detail::PlanarRelativePoseCost(z, informationSqrt<3>(I)));
    }
    Eigen::Matrix<double, 6, 6> I;
    for (int r = 0; r < 6; ++r)
        for (int k = 0; k < 6; ++k) I(r, k) = info(kSe3FromMrpt[r], kSe3FromMrpt[k]);
    const Eigen::Vector3d zt(c.mean.x(), c.mean.y(), c.mean.z());
    const Eigen::Quaterniond zq(c.mean.getRotationMatrix().asEigen());
    if (scaleJacobian) {
        return new ceres::AutoDiffCostFunction<detail::ScaledSe3RelativePoseCost, 6, 3, 4, 3, 4,
                                               2>(
            new detail::ScaledSe3RelativePoseCost(zt, zq, *scaleJacobian, informationSqrt<6>(I)));
    }
    return new ceres::AutoDiffCostFunction<detail::Se3RelativePoseCost, 6, 3, 4, 3, 4>(
        new detail::Se3RelativePoseCost(zt, zq, informationSqrt<6>(I)));
}

ceres::LossFunction* makeLoss(const std::string& name, double scale) {
    if (name == "none") return nullptr;
    if (name == "huber") return new ceres::HuberLoss(scale);
    if (name == "cauchy") return new ceres::CauchyLoss(scale);
    throw std::invalid_argument("unknown robust loss '" + name + "' (none, huber, cauchy)");
}

double squaredNorm(ceres::CostFunction& cost, std::vector<double*> blocks, int dim) {
    double r[6] = {0, 0, 0, 0, 0, 0};
    cost.Evaluate(blocks.data(), r, nullptr);
    double s = 0;
    for (int k = 0; k < dim; ++k) s += r[k] * r[k];
    return s;
}

std::vector<double*> blocksOf(NodeState& a, NodeState& b, bool planar) {
    if (planar) return {a.planar, b.planar};
    return {a.t, a.q, b.t, b.q};
}

}  // namespace

PoseGraphSolver::PoseGraphSolver(Options options) : options_(std::move(options)) {
    delete makeLoss(options_.robustLoss, options_.robustScale);  // validates the name
}

double PoseGraphSolver::squaredResidual(const Graph& graph, TNodeID from, TNodeID to,
                                        const Constraint& c) const {
    NodeState a = stateOf(graph.nodes.at(from)), b = stateOf(graph.nodes.at(to));
    std::unique_ptr<ceres::CostFunction> cost(makeCost(c, options_.planar));
    return squaredNorm(*cost, blocksOf(a, b, options_.planar), options_.planar ? 3 : 6);
}

namespace {

/** One solve's Ceres problem over the edges touching the moving nodes. Loop closures go
 * through a swappable loss so the same problem is solved plain, then robust. */
struct GraphProblem {
    std::map<TNodeID, NodeState> states;
    std::unique_ptr<ceres::Problem> problem;
    struct Closure {
        std::size_t index;  // into the caller's loopClosures
        ceres::LossFunctionWrapper* loss;
    };
    std::vector<Closure> closures;
    std::size_t edges{0};
    TNodeID gauge{std::numeric_limits<TNodeID>::max()};  // held fixed when nothing else is
    // (on the heap: Ceres keeps its address, and the problem is moved out of buildProblem)
    std::unique_ptr<double[]> mapUp{new double[3]{0, 0, 1}};
    std::unique_ptr<double[]> mapHeight{new double[1]{0}};
    bool mapUpFree{false}, mapHeightUsed{false};
    std::unique_ptr<double[]> wheelScale{new double[2]{0, 0}};  // (left, right)
    bool wheelScaleUsed{false}, wheelScaleFree{false};

    void setLoss(const std::string& name, double scale) {
        for (auto& c : closures) c.loss->Reset(makeLoss(name, scale), ceres::TAKE_OWNERSHIP);
    }
};

void holdConstant(ceres::Problem& problem, NodeState& s, bool planar) {
    if (planar) {
        problem.SetParameterBlockConstant(s.planar);
    } else {
        problem.SetParameterBlockConstant(s.t);
        problem.SetParameterBlockConstant(s.q);
    }
}

using EdgeIt = Graph::edges_map_t::const_iterator;

/** The edges a solve involves: all of them, or those touching the window. Edges are keyed by
 * (from, to), so a window node's outgoing edges are one range; the edges coming into it are
 * the odometry edge from its predecessor and loop closures (the caller's list), so no solve
 * walks the whole graph. */
std::vector<EdgeIt> edgesOf(const Graph& graph, const std::vector<LoopClosure>& loopClosures,
                            const std::set<TNodeID>& window) {
    std::vector<EdgeIt> out;
    if (window.empty()) {
        for (auto it = graph.edges.begin(); it != graph.edges.end(); ++it) out.push_back(it);
        return out;
    }
    const auto outgoing = [&](TNodeID id, bool onlyIntoWindow) {
        const auto end = graph.edges.lower_bound({id + 1, 0});
        for (auto it = graph.edges.lower_bound({id, 0}); it != end; ++it) {
            if (!onlyIntoWindow || window.count(it->first.second)) out.push_back(it);
        }
    };
    for (const TNodeID id : window) {
        outgoing(id, false);
        if (id > 0 && !window.count(id - 1)) outgoing(id - 1, true);
    }
    for (const auto& lc : loopClosures) {
        if (lc.rejected || window.count(lc.from) || !window.count(lc.to)) continue;
        const auto range = graph.edges.equal_range({lc.from, lc.to});
        for (auto it = range.first; it != range.second; ++it) {
            if (it->second.mean == lc.constraint.mean) out.push_back(it);
        }
    }
    // Each edge once, in the order found (by node ID, then closure order): the order of the
    // residual blocks is the order Ceres sums in, so an order by address would make the
    // result's last bits depend on where the heap put the edges.
    std::vector<EdgeIt> unique;
    std::unordered_set<const void*> seen;
    for (const EdgeIt& it : out) {
        if (seen.insert(&*it).second) unique.push_back(it);
    }
    return unique;
}

/** Each node in the problem with a measured up: a prior on its roll and pitch against the
 * map's up (a variable on the unit sphere when `solveMapUp`, else held). */
void addAttitudePriors(GraphProblem& gp, const AttitudePriors& priors, bool solveMapUp) {
    auto& problem = *gp.problem;
    for (int k = 0; k < 3; ++k) gp.mapUp[k] = priors.mapUp[k];
    gp.mapHeight[0] = priors.mapHeight;
    // Heights are along the map's up: with no node's up to hold it, the nodes' own plane could
    // stand on its edge (a straight walk), so they wait for one (an IMU that never reported).
    const bool anyUp = std::any_of(priors.nodes.begin(), priors.nodes.end(),
                                   [](const auto& p) { return p.second.sigma > 0; });
    bool any = false;
    for (auto& [id, st] : gp.states) {
        const auto p = priors.nodes.find(id);
        if (p == priors.nodes.end()) continue;
        if (p->second.sigma > 0 && (solveMapUp || !problem.IsParameterBlockConstant(st.q))) {
            problem.AddResidualBlock(
                new ceres::AutoDiffCostFunction<detail::AttitudePriorCost, 3, 4, 3>(
                    new detail::AttitudePriorCost(p->second.up, p->second.sigma)),
                nullptr, st.q, gp.mapUp.get());
            any = true;
        }
        if (anyUp && p->second.heightSigma > 0 &&
            (solveMapUp || !problem.IsParameterBlockConstant(st.t))) {
            problem.AddResidualBlock(
                new ceres::AutoDiffCostFunction<detail::HeightPriorCost, 1, 3, 3, 1>(
                    new detail::HeightPriorCost(p->second.heightSigma, p->second.height)),
                nullptr, st.t, gp.mapUp.get(), gp.mapHeight.get());
            any = gp.mapHeightUsed = true;
        }
    }
    if (!any) return;
    problem.SetManifold(gp.mapUp.get(), new ceres::SphereManifold<3>);
    gp.mapUpFree = solveMapUp;
    if (!solveMapUp) {
        problem.SetParameterBlockConstant(gp.mapUp.get());
        if (gp.mapHeightUsed) problem.SetParameterBlockConstant(gp.mapHeight.get());
    }
}

template <typename Moves>
GraphProblem buildProblem(const Graph& graph, const std::vector<LoopClosure>& loopClosures,
                          const std::vector<EdgeIt>& edges, const Moves& moves, bool planar,
                          const AttitudePriors* attitude, bool solveMapUp,
                          const WheelScale* wheels, bool solveWheelScale) {
    std::map<std::pair<TNodeID, TNodeID>, std::vector<std::size_t>> closureIndex;
    for (std::size_t k = 0; k < loopClosures.size(); ++k) {
        const auto& lc = loopClosures[k];
        if (!lc.rejected && (moves(lc.from) || moves(lc.to)))
            closureIndex[{lc.from, lc.to}].push_back(k);
    }
    GraphProblem gp;
    ceres::Problem::Options po;
    po.manifold_ownership = ceres::TAKE_OWNERSHIP;
    gp.problem = std::make_unique<ceres::Problem>(po);
    auto& problem = *gp.problem;
    const bool scaled = wheels && wheels->active();
    if (scaled) {
        gp.wheelScale[0] = wheels->scale[0];
        gp.wheelScale[1] = wheels->scale[1];
    }
    for (const EdgeIt& e : edges) {
        const auto& [ends, c] = *e;
        const auto [from, to] = ends;
        if (!moves(from) && !moves(to)) continue;
        if (!graph.nodes.count(from) || !graph.nodes.count(to)) continue;
        for (TNodeID id : {from, to}) {
            if (gp.states.count(id)) continue;
            auto& st = gp.states[id] = stateOf(graph.nodes.at(id));
            if (!planar) problem.AddParameterBlock(st.q, 4, new ceres::EigenQuaternionManifold);
        }
        std::size_t closure = std::string::npos;
        const auto found = closureIndex.find(ends);
        if (found != closureIndex.end()) {
            for (const std::size_t k : found->second) {
                if (loopClosures[k].constraint.mean == c.mean) closure = k;
            }
        }
        ceres::LossFunctionWrapper* loss = nullptr;
        if (closure != std::string::npos) {
            loss = new ceres::LossFunctionWrapper(nullptr, ceres::TAKE_OWNERSHIP);
            gp.closures.push_back({closure, loss});
        }
        // An odometry edge the wheels measured: corrected by their scales.
        const Eigen::Matrix<double, 3, 2>* jacobian = nullptr;
        if (scaled && closure == std::string::npos) {
            const auto found = wheels->edges.find(ends);
            if (found != wheels->edges.end()) jacobian = &found->second;
        }
        auto blocks = blocksOf(gp.states[from], gp.states[to], planar);
        if (jacobian) {
            blocks.push_back(gp.wheelScale.get());
            problem.AddResidualBlock(makeCost(c, planar, jacobian), nullptr, blocks);
            gp.wheelScaleUsed = true;
        } else {
            problem.AddResidualBlock(makeCost(c, planar), loss, blocks);
        }
        ++gp.edges;
    }
    // The scales are the run's: only a full solve sees enough of it to move them.
    if (gp.wheelScaleUsed) {
        gp.wheelScaleFree = solveWheelScale;
        if (solveWheelScale) {
            problem.AddResidualBlock(
                new ceres::AutoDiffCostFunction<detail::WheelScalePriorCost, 2, 2>(
                    new detail::WheelScalePriorCost(wheels->sigma)),
                nullptr, gp.wheelScale.get());
        } else {
            problem.SetParameterBlockConstant(gp.wheelScale.get());
        }
    }
    // Fixed: nodes outside the window and the graph's root (the gauge: the map frame is where
    // the run started); without the root, the lowest node ID.
    bool anyFixed = false;
    for (auto& [id, st] : gp.states) {
        if (moves(id) && id != graph.root) continue;
        anyFixed = true;
        holdConstant(problem, st, planar);
    }
    if (!anyFixed && !gp.states.empty()) {
        gp.gauge = gp.states.begin()->first;
        holdConstant(problem, gp.states.begin()->second, planar);
    }
    if (attitude && !planar) addAttitudePriors(gp, *attitude, solveMapUp);
    return gp;
}

}  // namespace

PoseGraphSolver::Report PoseGraphSolver::solve(Graph& graph, std::vector<LoopClosure>& loopClosures,
                                               const std::set<TNodeID>& window, bool reject,
                                               AttitudePriors* attitude,
                                               WheelScale* wheels) const {
    const auto t0 = std::chrono::steady_clock::now();
    Report report;
    const bool planar = options_.planar;
    const auto moves = [&](TNodeID id) {
        return id >= options_.fixedBelow && (window.empty() || window.count(id) > 0);
    };
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    so.max_num_iterations = options_.maxIterations;
    so.function_tolerance = options_.functionTolerance;
    so.num_threads = 1;
    so.logging_type = ceres::SILENT;

    for (int round = 0;; ++round) {
        // The map's up is the whole graph's: only a full solve of a graph free to turn solves it.
        const bool solveMapUp = window.empty() && options_.fixedBelow == 0;
        GraphProblem gp = buildProblem(graph, loopClosures, edgesOf(graph, loopClosures, window),
                                       moves, planar, attitude, solveMapUp, wheels,
                                       window.empty());
        if (gp.edges == 0) break;
        // Least squares judges: at its optimum a closure's squared Mahalanobis residual is
        // chi-square distributed, so the gate means what it says. A robust solve points at the
        // culprit: it lets the wrong closure go instead of bending the right ones towards it.
        const auto runSolve = [&](const std::string& loss) {
            gp.setLoss(loss, options_.robustScale);
            ceres::Solver::Summary summary;
            ceres::Solve(so, gp.problem.get(), &summary);
            if (report.solves == 0) report.initialCost = summary.initial_cost;
            report.finalCost = summary.final_cost;
            report.iterations += static_cast<int>(summary.iterations.size());
            report.converged = summary.termination_type == ceres::CONVERGENCE;
            ++report.solves;
            report.edges = gp.edges;
            report.variableNodes = report.fixedNodes = 0;
            if (gp.mapUpFree) {
                attitude->mapUp = Eigen::Map<const Eigen::Vector3d>(gp.mapUp.get()).normalized();
                if (gp.mapHeightUsed) attitude->mapHeight = gp.mapHeight[0];
            }
            if (gp.wheelScaleFree)
                wheels->scale = Eigen::Map<const Eigen::Vector2d>(gp.wheelScale.get());
            for (const auto& [id, st] : gp.states) {
                if (moves(id) && id != gp.gauge && id != graph.root) {
                    graph.nodes[id] = poseOf(st, graph.nodes.at(id), planar);
                    ++report.variableNodes;
                } else {
                    ++report.fixedNodes;
                }
            }
        };
        std::map<std::size_t, double> plainChi2;  // closure index -> at the least-squares optimum
        const auto worstClosure = [&](bool plain) {
            std::pair<double, std::size_t> worst{-1, std::string::npos};
            for (const auto& c : gp.closures) {
                const auto& lc = loopClosures[c.index];
                const double r2 = squaredResidual(graph, lc.from, lc.to, lc.constraint);
                if (plain) plainChi2[c.index] = r2;
                worst = std::max(worst, {r2, c.index});
            }
            return worst;
        };
        runSolve("none");
        const auto [worstPlain, plainIdx] = worstClosure(true);
        if (!reject || plainIdx == std::string::npos || worstPlain <= options_.rejectionChi2 ||
            round >= options_.maxRejectionsPerSolve) {
            break;
        }
        std::size_t culprit = plainIdx;
        if (options_.robustLoss != "none") {
            runSolve(options_.robustLoss);
            culprit = worstClosure(false).second;
        }
        auto& lc = loopClosures[culprit];
        lc.rejected = true;
        lc.rejectionChi2 = plainChi2.at(culprit);
        eraseEdge(graph, lc.from, lc.to, lc.constraint);
        report.rejected.push_back(lc);
    }
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return report;
}

}  // namespace lodestone::graphslam
