#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/gso/CeresGSO.h>

#include <algorithm>
#include <map>

namespace lodestone::graphslam {

CeresGSO::CeresGSO() {
    setClassName("CeresGSO");
    wheels_.sigma = params_.wheelScaleSigma;
    solver_ = std::make_unique<PoseGraphSolver>(params_.solver);
}

void CeresGSO::configure(const mrpt::config::CConfigFileBase& ini) {
    config::IniSection s(ini, "CeresGSO", config::sourceName(ini));
    Params p = params_;  // all or nothing: a failed read leaves the optimizer as it was
    auto& o = p.solver;
    const std::string mode = s.getString("mode", o.planar ? "planar" : "se3");
    if (mode != "planar" && mode != "se3") s.fail("mode", "must be planar or se3");
    o.planar = mode == "planar";
    o.robustLoss = s.getString("robust_loss", o.robustLoss);
    o.robustScale = s.getDouble("robust_scale", o.robustScale);
    const double chi2 = s.getDouble("rejection_chi2", 0);
    o.rejectionChi2 = chi2 > 0 ? chi2 : (o.planar ? kChi2Planar999 : kChi2Se3999);
    o.maxIterations = s.getInt("max_iterations", o.maxIterations);
    p.localWindow = s.getInt("local_window", p.localWindow);
    p.fullSolveGrowth = s.getDouble("full_solve_growth", p.fullSolveGrowth);
    p.backgroundMergeNodes = s.getInt("background_merge_nodes", p.backgroundMergeNodes);
    p.wheelScaleSigma = s.getDouble("wheel_scale_sigma", p.wheelScaleSigma);
    if (!(p.wheelScaleSigma >= 0)) s.fail("wheel_scale_sigma", "must be >= 0 (0: not estimated)");
    if (p.backgroundMergeNodes < 0)
        s.fail("background_merge_nodes", "must be >= 0 (0: in the frame loop)");
    if (o.robustLoss != "none" && o.robustLoss != "huber" && o.robustLoss != "cauchy") {
        s.fail("robust_loss", "must be none, huber or cauchy");
    }
    if (!(o.robustScale > 0)) s.fail("robust_scale", "must be > 0");
    if (chi2 < 0) s.fail("rejection_chi2", "must be >= 0");
    if (o.maxIterations < 1) s.fail("max_iterations", "must be >= 1");
    if (p.localWindow < 1) s.fail("local_window", "must be >= 1");
    if (!(p.fullSolveGrowth > 0)) s.fail("full_solve_growth", "must be > 0");
    s.finish();
    params_ = p;
    wheels_.sigma = p.wheelScaleSigma;
    solver_ = std::make_unique<PoseGraphSolver>(o);
}

void CeresGSO::adoptMap(TNodeID count) { nodes_at_last_full_ = count; }

void CeresGSO::holdFixed(TNodeID count) {
    params_.solver.fixedBelow = count;
    solver_ = std::make_unique<PoseGraphSolver>(params_.solver);
}

void CeresGSO::addAttitudePrior(TNodeID id, const AttitudePrior& prior) {
    if (params_.solver.planar || !(prior.sigma > 0 || prior.heightSigma > 0)) return;
    // The map's up starts as the first prior's, turned into the map frame by its node's pose,
    // and the level heights are above (the floor, the carrier's common height) as the first
    // node with a height puts it; full solves refine both.
    if (m_graph && m_graph->nodes.count(id)) {
        const auto& pose = m_graph->nodes.at(id);
        if (attitude_.nodes.empty())
            attitude_.mapUp = pose.getRotationMatrix().asEigen() * prior.up;
        if (!map_height_set_ && prior.heightSigma > 0) {
            attitude_.mapHeight =
                attitude_.mapUp.dot(Eigen::Vector3d(pose.x(), pose.y(), pose.z())) - prior.height;
            map_height_set_ = true;
        }
    }
    attitude_.nodes[id] = prior;
}

void CeresGSO::addWheelScaleJacobian(TNodeID from, TNodeID to,
                                     const Eigen::Matrix<double, 3, 2>& jacobian) {
    if (wheels_.sigma > 0) wheels_.edges[{from, to}] = jacobian;
}

void CeresGSO::calibrateEdges(Graph& graph) const {
    if (!wheels_.active()) return;
    // (as the solves: a closure between the same two nodes is not the wheels')
    std::multimap<std::pair<TNodeID, TNodeID>, const Constraint*> closures;
    for (const auto& lc : closures_)
        closures.emplace(std::make_pair(lc.from, lc.to), &lc.constraint);
    for (const auto& [ends, jacobian] : wheels_.edges) {
        const Eigen::Vector3d d = jacobian * wheels_.scale;
        const auto range = graph.edges.equal_range(ends);
        const auto sameEnds = closures.equal_range(ends);
        for (auto it = range.first; it != range.second; ++it) {
            auto& m = it->second.mean;
            if (std::any_of(sameEnds.first, sameEnds.second,
                            [&](const auto& c) { return c.second->mean == m; }))
                continue;
            m = mrpt::poses::CPose3D(m.x() + d.x(), m.y() + d.y(), m.z(), m.yaw() + d.z(),
                                     m.pitch(), m.roll());
        }
    }
}

void CeresGSO::addLoopClosures(const std::vector<LoopClosure>& closures) {
    for (const auto& lc : closures) {
        closures_.push_back(lc);
        pending_.emplace_back(lc.from, lc.to);
    }
    if (!closures.empty()) closures_since_full_ = true;
}

void CeresGSO::addRelocationClosures(const std::vector<LoopClosure>& closures,
                                     const std::set<TNodeID>& movable) {
    for (const auto& lc : closures) closures_.push_back(lc);
    if (closures.empty() || movable.empty()) return;
    discardBackground();  // (its snapshot has the moved group where it was)
    closures_since_full_ = true;
    absorb(solver_->solve(*m_graph, closures_, movable, false, priors(), wheels()), false);
}

bool CeresGSO::updateState(mrpt::obs::CActionCollection::Ptr, mrpt::obs::CSensoryFrame::Ptr,
                           mrpt::obs::CObservation::Ptr) {
    just_full_ = false;
    mergeBackgroundIfDue();
    if (pending_.empty()) return just_full_;
    const std::size_t n = m_graph->nodes.size();
    if (closures_since_full_ && !background_ &&
        static_cast<double>(n) >= (1 + params_.fullSolveGrowth) * nodes_at_last_full_) {
        if (params_.backgroundMergeNodes == 0) {
            optimizeGraph();
            return true;
        }
        // On a snapshot, merged a fixed number of nodes later; the new closures are solved
        // locally below in the meantime.
        background_ = std::make_unique<BackgroundSolve>(
            params_.solver, *m_graph, closures_,
            n + static_cast<std::size_t>(params_.backgroundMergeNodes), priors(), wheels());
        ++stats_.backgroundSolves;
        nodes_at_last_full_ = n;
        closures_since_full_ = false;
    }
    std::set<TNodeID> window;
    const auto w = static_cast<TNodeID>(params_.localWindow);
    for (const auto& [from, to] : pending_) {
        for (TNodeID end : {from, to}) {
            for (TNodeID id = end > w ? end - w : 0; id <= end + w; ++id) {
                if (m_graph->nodes.count(id)) window.insert(id);
            }
        }
    }
    absorb(solver_->solve(*m_graph, closures_, window, false, priors(), wheels()), false);
    // A window cannot tell a wrong closure from a right one whose correction reaches beyond it:
    // if a new closure still disagrees, the full graph decides.
    for (const auto& lc : closures_) {
        if (lc.rejected) continue;
        const bool isNew = std::find(pending_.begin(), pending_.end(),
                                     std::make_pair(lc.from, lc.to)) != pending_.end();
        if (isNew && solver_->squaredResidual(*m_graph, lc.from, lc.to, lc.constraint) >
                         params_.solver.rejectionChi2) {
            ++stats_.escalations;
            optimizeGraph();
            return true;
        }
    }
    pending_.clear();
    return true;
}

void CeresGSO::mergeBackgroundIfDue() {
    if (!background_ || m_graph->nodes.size() < background_->mergeAtNodes()) return;
    double waited = 0;
    absorb(background_->mergeInto(*m_graph, closures_, &waited, priors(), wheels()), true);
    stats_.backgroundWaitSeconds += waited;
    // Closures that came after the snapshot: solved again around them, on the merged graph.
    for (std::size_t k = background_->closuresAtLaunch(); k < closures_.size(); ++k) {
        if (!closures_[k].rejected) pending_.emplace_back(closures_[k].from, closures_[k].to);
    }
    background_.reset();
    just_full_ = true;
}

void CeresGSO::discardBackground() {
    if (!background_) return;
    background_.reset();  // (waits for the thread, drops its result)
    ++stats_.backgroundDiscarded;
    closures_since_full_ = true;
}

void CeresGSO::optimizeGraph() {
    discardBackground();
    pending_.clear();
    absorb(solver_->solve(*m_graph, closures_, {}, true, priors(), wheels()), true);
    nodes_at_last_full_ = m_graph->nodes.size();
    closures_since_full_ = false;
    just_full_ = true;
}

void CeresGSO::finish() {
    // An odometry chain is already at its optimum; anything with closures (or re-anchored
    // segments) gets one last full solve.
    // (so does one with measured ups: they level the chain)
    if (!closures_.empty() || !attitude_.nodes.empty()) optimizeGraph();
}

void CeresGSO::absorb(const PoseGraphSolver::Report& r, bool full) {
    (full ? stats_.fullSolves : stats_.localSolves) += 1;
    (full ? stats_.fullSeconds : stats_.localSeconds) += r.seconds;
    stats_.iterations += static_cast<std::size_t>(r.iterations);
    stats_.rejected += r.rejected.size();
    for (const auto& rej : r.rejected) {
        MRPT_LOG_INFO_STREAM("rejected loop closure " << rej.from << " -> " << rej.to << " from "
                                                      << rej.source << ": chi2 "
                                                      << rej.rejectionChi2);
    }
}

JsonObject CeresGSO::describe() const {
    const auto& o = params_.solver;
    JsonObject params;
    params.set("mode", o.planar ? "planar" : "se3")
        .set("robust_loss", o.robustLoss)
        .set("robust_scale", o.robustScale)
        .set("rejection_chi2", o.rejectionChi2)
        .set("max_iterations", o.maxIterations)
        .set("local_window", params_.localWindow)
        .set("full_solve_growth", params_.fullSolveGrowth)
        .set("background_merge_nodes", params_.backgroundMergeNodes)
        .set("wheel_scale_sigma", params_.wheelScaleSigma);
    std::vector<JsonObject> rejected;
    for (const auto& lc : closures_) {
        if (!lc.rejected) continue;
        rejected.push_back(JsonObject()
                               .set("from", static_cast<long long>(lc.from))
                               .set("to", static_cast<long long>(lc.to))
                               .set("source", lc.source)
                               .set("chi2", lc.rejectionChi2));
    }
    JsonObject stats;
    stats.set("local_solves", stats_.localSolves)
        .set("full_solves", stats_.fullSolves)
        .set("iterations", stats_.iterations)
        .set("local_seconds", stats_.localSeconds)
        .set("full_seconds", stats_.fullSeconds)
        .set("escalations", stats_.escalations)
        .set("background_solves", stats_.backgroundSolves)
        .set("background_discarded", stats_.backgroundDiscarded)
        .set("background_wait_seconds", stats_.backgroundWaitSeconds)
        .set("loop_closures", closures_.size())
        .set("attitude_priors", attitude_.nodes.size())
        .set("wheel_scale_edges", wheels_.edges.size())
        .set("wheel_scale_left", wheels_.scale[0])
        .set("wheel_scale_right", wheels_.scale[1])
        .set("rejected", stats_.rejected);
    return JsonObject()
        .set("class", getClassName())
        .set("params", params)
        .set("stats", stats)
        .set("rejected_loop_closures", rejected);
}

}  // namespace lodestone::graphslam
