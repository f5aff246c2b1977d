// MagneticGpERD, the second half: a matched bundle made into loop-closure edges - the GP
// shift along the target's path (paper 000 eq. 3), then either node-to-node edges along that
// path (§2.3) or the stretch moved in the plane against every earlier pass found there.
#include <lodestone/graphslam/erd/magnetic/MagneticGpERD.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace lodestone::graphslam {

bool MagneticGpERD::nodeAtTravel(double s, int segment, TNodeID& k, double& frac) const {
    const auto it = std::upper_bound(path_.travel.begin(), path_.travel.end(), s);
    if (it == path_.travel.begin() || it == path_.travel.end()) return false;
    const auto next = static_cast<std::size_t>(it - path_.travel.begin());
    k = static_cast<TNodeID>(next - 1);
    if (path_.segment[k] != segment || path_.segment[next] != segment) return false;
    const double span = path_.travel[next] - path_.travel[k];
    frac = span > 0 ? (s - path_.travel[k]) / span : 0.0;
    return true;
}

std::size_t MagneticGpERD::windowStart(const magnetic::BundleMatch& b) const {
    const auto& sn = track_->supernodes();
    const std::size_t qEnd = sn[b.lastQuery].last;
    const auto window =
        static_cast<std::size_t>(std::lround(params_.gpWindow / params_.track.step));
    return std::max(sn[b.firstQuery].first, qEnd > window ? qEnd - window : 0);
}

std::optional<MagneticGpERD::PathFit> MagneticGpERD::fitAlongPath(const magnetic::BundleMatch& b,
                                                                  std::size_t qBegin) const {
    const auto& samples = track_->samples();
    const auto& sn = track_->supernodes();
    const std::size_t qEnd = sn[b.lastQuery].last;
    const int tSegment = sn[b.lastTarget].segment;
    // Target readings over the query window's travel moved by the offset, plus the scan range.
    const double margin = params_.shift.maxShift + 2 * params_.track.step;
    const double lo = samples[qBegin].s + b.offset - margin,
                 hi = samples[qEnd - 1].s + b.offset + margin;
    const auto first =
        std::lower_bound(samples.begin(), samples.end(), lo,
                         [](const magnetic::TrackSample& a, double v) { return a.s < v; });
    std::vector<double> tx;
    std::vector<Eigen::VectorXf> ty;
    for (auto it = first; it != samples.end() && it->s <= hi; ++it) {
        if (it->segment != tSegment) return std::nullopt;  // the target stretch crosses a kidnap
        tx.push_back(it->s);
        ty.push_back(it->value);
    }
    const double expected = (hi - lo) / params_.track.step;
    if (tx.size() < 0.9 * expected) return std::nullopt;  // a gap in the target's readings
    const int C = track_->channels();
    Eigen::MatrixXd T(static_cast<Eigen::Index>(tx.size()), C);
    for (std::size_t i = 0; i < tx.size(); ++i)
        T.row(static_cast<Eigen::Index>(i)) = ty[i].cast<double>().transpose();
    std::vector<double> qx;
    Eigen::MatrixXd Q(static_cast<Eigen::Index>(qEnd - qBegin), C);
    for (std::size_t i = qBegin; i < qEnd; ++i) {
        qx.push_back(samples[i].s + b.offset);
        Q.row(static_cast<Eigen::Index>(i - qBegin)) = samples[i].value.cast<double>().transpose();
    }
    magnetic::GaussianProcess1D gp(params_.gp);
    gp.fit(tx, T);
    PathFit fit;
    fit.qBegin = qBegin;
    fit.qEnd = qEnd;
    fit.shift = magnetic::scanShift(gp, qx, Q, params_.shift);
    if (!fit.shift.valid) return std::nullopt;
    return fit;
}

void MagneticGpERD::align(const std::vector<magnetic::BundleMatch>& bundles, const PathFit& fit) {
    const magnetic::BundleMatch& b = bundles.front();
    const auto& shift = fit.shift;
    const std::size_t qBegin = fit.qBegin, qEnd = fit.qEnd;
    if (shift.normalizedRms > params_.maxNormalizedRms) {
        ++stats_.gpRejected;
        return;
    }
    ++stats_.alignments;
    Record rec;
    rec.querySupernode = b.lastQuery;
    rec.offset = b.offset;
    rec.shift = shift.shift;
    rec.shiftSigma = shift.sigma;
    rec.normalizedRms = shift.normalizedRms;
    rec.cost = b.meanCost;
    if (params_.alignment == Params::Alignment::Plane) {
        if (!alignInPlane(bundles, qBegin, qEnd, shift.shift, rec)) ++stats_.planeRejected;
    } else {
        addPathEdges(b, qBegin, qEnd, shift, rec);
    }
    commitEdges(rec);
}

void MagneticGpERD::addPathEdges(const magnetic::BundleMatch& b, std::size_t qBegin,
                                 std::size_t qEnd, const magnetic::ShiftResult& shift,
                                 Record& rec) {
    const auto& samples = track_->samples();
    const int tSegment = track_->supernodes()[b.lastTarget].segment;
    // §2.3: the bundle constraint subdivided into node-to-node edges.
    const std::size_t firstNode = samples[qBegin].node, lastNode = samples[qEnd - 1].node;
    const double sigmaAlong2 = shift.sigma * shift.sigma + params_.sigmaAlong * params_.sigmaAlong;
    for (std::size_t qn = firstNode; qn <= lastNode; ++qn) {
        if (constrained_[qn] || qn % static_cast<std::size_t>(params_.edgeEvery) != 0) continue;
        TNodeID k;
        double frac;
        if (!nodeAtTravel(path_.travel[qn] + b.offset + shift.shift, tSegment, k, frac)) continue;
        const auto e = m_graph->edges.find({k, k + 1});
        if (e == m_graph->edges.end()) continue;
        const auto& d = e->second.mean;
        const mrpt::poses::CPose2D mean(frac * d.x(), frac * d.y(), frac * d.yaw());
        // Along the target's path: the GP's precision; across it and in heading: loose.
        const Eigen::Matrix2d S =
            alongAcross(d, sigmaAlong2, params_.sigmaCross * params_.sigmaCross);
        addEdge(k, qn, mean, S, params_.sigmaYaw * params_.sigmaYaw, rec);
    }
}

void MagneticGpERD::addEdge(TNodeID target, std::size_t queryNode,
                            const mrpt::poses::CPose2D& mean, const Eigen::Matrix2d& positionCov,
                            double yawVariance, Record& rec) {
    rec.pending.push_back({target, queryNode, mean, positionCov, yawVariance});
    constrained_[queryNode] = true;
}

void MagneticGpERD::commitEdges(Record& rec) {
    // One alignment measured one shift, one offset across and one heading for all its edges:
    // summed as independent they would claim sqrt(n) times what it knows.
    const double share = params_.edgesShareAlignment
                             ? static_cast<double>(std::max<std::size_t>(1, rec.pending.size()))
                             : 1.0;
    for (const auto& e : rec.pending) {
        mrpt::poses::CPosePDFGaussian z;
        z.mean = e.mean;
        z.cov.setZero();
        for (int r = 0; r < 2; ++r)
            for (int c = 0; c < 2; ++c) z.cov(r, c) = share * e.positionCov(r, c);
        z.cov(2, 2) = share * e.yawVariance;
        const Constraint c = planarConstraint(z);
        const auto q = static_cast<TNodeID>(e.queryNode);
        // The edges of one alignment are one piece of evidence for the relocalizer.
        // (field-map closures are scored by their evidence and logged apart: closures.csv's
        // per-matcher precision then tells the two methods apart)
        if (rec.fieldMap) {
            registerClosure(e.target, q, c, records_.size(), false, rec.logRatio,
                            getClassName() + ".map");
        } else {
            registerClosure(e.target, q, c, records_.size(), false, -rec.normalizedRms);
        }
        // The query node is now known as well as the alignment says (in the map frame).
        path_.pinClosure(q, m_graph->nodes.at(e.target).yaw(), e.positionCov, e.yawVariance);
        rec.edges.emplace_back(e.target, q);
        rec.constraints.push_back(c);
        ++stats_.edges;
    }
    rec.pending.clear();
    if (!rec.edges.empty()) records_.push_back(std::move(rec));
}

void MagneticGpERD::addMovedNodeEdge(std::size_t qn, TNodeID target, const Eigen::Vector2d& moved0,
                                     double turn, const magnetic::PlanarAlignmentResult& r,
                                     Record& rec) {
    const auto& q = m_graph->nodes.at(static_cast<TNodeID>(qn));
    const Eigen::Vector2d moved = r.apply(moved0);
    const mrpt::poses::CPose2D corrected(moved.x(), moved.y(), q.yaw() + turn + r.delta[2]);
    const auto& tk = m_graph->nodes.at(target);
    const mrpt::poses::CPose2D there(tk.x(), tk.y(), tk.yaw());
    // The alignment's covariance at this node (the turn's lever arm included), in the target's
    // frame.
    Eigen::Matrix2d J90;
    J90 << 0, -1, 1, 0;
    Eigen::Matrix<double, 2, 3> J;
    J << Eigen::Matrix2d::Identity(), J90 * (moved0 - r.pivot);
    const Eigen::Matrix2d S = J * r.covariance * J.transpose() +
                              params_.sigmaAlong * params_.sigmaAlong * Eigen::Matrix2d::Identity();
    const Eigen::Matrix2d Rk = Eigen::Rotation2Dd(tk.yaw()).toRotationMatrix();
    addEdge(target, qn, corrected - there, Rk.transpose() * S * Rk,
            r.covariance(2, 2) + params_.sigmaYaw * params_.sigmaYaw, rec);
}

bool MagneticGpERD::positionAtTravel(double s, int segment, Eigen::Vector2d& p) const {
    TNodeID k;
    double frac;
    if (!nodeAtTravel(s, segment, k, frac)) return false;
    const auto a = positionOf(k), b = positionOf(k + 1);
    p = Eigen::Vector2d(a.x + frac * (b.x - a.x), a.y + frac * (b.y - a.y));
    return true;
}

bool MagneticGpERD::alignInPlane(const std::vector<magnetic::BundleMatch>& bundles,
                                 std::size_t qBegin, std::size_t qEnd, double shift, Record& rec) {
    const auto& samples = track_->samples();
    const auto& sn = track_->supernodes();
    const magnetic::BundleMatch& best = bundles.front();
    const int qSegment = samples[qEnd - 1].segment;
    const int C = track_->channels();
    // The query window where the graph has it now, and where the path alignment puts it.
    std::vector<Eigen::Vector2d> here, there;
    for (std::size_t i = qBegin; i < qEnd; ++i) {
        Eigen::Vector2d a, b;
        if (!positionAtTravel(samples[i].s, qSegment, a) ||
            !positionAtTravel(samples[i].s + best.offset + shift, sn[best.lastTarget].segment, b))
            return false;
        here.push_back(a);
        there.push_back(b);
    }
    const auto m = static_cast<Eigen::Index>(here.size());
    // (dynamic-size on purpose: GCC 12 warns falsely inside umeyama for 2 x N fixed rows)
    Eigen::MatrixXd from(2, m), to(2, m);
    for (Eigen::Index i = 0; i < m; ++i) {
        from.col(i) = here[static_cast<std::size_t>(i)];
        to.col(i) = there[static_cast<std::size_t>(i)];
    }
    const Eigen::Matrix3d T0 = Eigen::umeyama(from, to, false);  // rigid, query -> target
    Eigen::MatrixX2d start(m, 2);
    Eigen::MatrixXd Q(m, C);
    for (Eigen::Index i = 0; i < m; ++i) {
        start.row(i) = (T0.topLeftCorner<2, 2>() * from.col(i) + T0.topRightCorner<2, 1>()).transpose();
        Q.row(i) = samples[qBegin + static_cast<std::size_t>(i)].value.cast<double>().transpose();
    }
    // Every earlier pass the bundles found here: their readings where the graph has them.
    std::vector<Eigen::Vector2d> at;
    std::vector<Eigen::VectorXf> values;
    for (const auto& bb : bundles) {
        const int seg = sn[bb.lastTarget].segment;
        const double lo = samples[qBegin].s + bb.offset - params_.planeMargin,
                     hi = samples[qEnd - 1].s + bb.offset + params_.planeMargin;
        auto it = std::lower_bound(samples.begin(), samples.end(), lo,
                                   [](const magnetic::TrackSample& a, double v) { return a.s < v; });
        for (int k = 0; it != samples.end() && it->s <= hi; ++it, ++k) {
            Eigen::Vector2d p;
            if (k % params_.planeSubsample != 0 || it->segment != seg || !positionAtTravel(it->s, seg, p))
                continue;
            at.push_back(p);
            values.push_back(it->value);
        }
    }
    if (at.size() < static_cast<std::size_t>(m) / 2) return false;
    Eigen::MatrixX2d P(static_cast<Eigen::Index>(at.size()), 2);
    Eigen::MatrixXd Y(static_cast<Eigen::Index>(at.size()), C);
    for (std::size_t i = 0; i < at.size(); ++i) {
        P.row(static_cast<Eigen::Index>(i)) = at[i].transpose();
        Y.row(static_cast<Eigen::Index>(i)) = values[i].cast<double>().transpose();
    }
    magnetic::GaussianProcess2D gp(params_.gp);
    gp.fit(P, Y);
    const auto r = magnetic::alignInPlane(gp, start, Q, params_.plane);
    if (!r.valid || r.normalizedRms > params_.maxNormalizedRms) return false;
    rec.plane = true;
    rec.planeDelta = r.delta;
    rec.normalizedRms = r.normalizedRms;
    // Each query node moved as its readings were: by T0, then by the plane alignment; tied to
    // the target node nearest where the path alignment put it.
    const double yaw0 = std::atan2(T0(1, 0), T0(0, 0));
    const std::size_t firstNode = samples[qBegin].node, lastNode = samples[qEnd - 1].node;
    for (std::size_t qn = firstNode; qn <= lastNode; ++qn) {
        if (constrained_[qn] || qn % static_cast<std::size_t>(params_.edgeEvery) != 0) continue;
        TNodeID k;
        double frac;
        if (!nodeAtTravel(path_.travel[qn] + best.offset + shift, sn[best.lastTarget].segment, k, frac))
            continue;
        if (frac > 0.5) ++k;
        const auto& q = m_graph->nodes.at(static_cast<TNodeID>(qn));
        const Eigen::Vector2d moved0 = T0.topLeftCorner<2, 2>() * Eigen::Vector2d(q.x(), q.y()) +
                                       T0.topRightCorner<2, 1>();
        addMovedNodeEdge(qn, k, moved0, yaw0, r, rec);
    }
    return true;
}

}  // namespace lodestone::graphslam
