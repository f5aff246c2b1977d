#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/relocalization/Relocalizer.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <stdexcept>

namespace lodestone::graphslam::relocalization {

Relocalizer::Params Relocalizer::readParams(const mrpt::config::CConfigFileBase& ini) {
    Params p;
    config::IniSection s(ini, "relocalization", config::sourceName(ini));
    const double chi2 = s.getDouble("consistency_chi2", 0);
    if (chi2 < 0) s.fail("consistency_chi2", "must be >= 0");
    if (chi2 > 0) p.consistencyChi2 = chi2;
    p.independentTravel = s.getDouble("independent_travel", p.independentTravel);
    p.mapSigmaXY = s.getDouble("map_sigma_xy", p.mapSigmaXY);
    p.mapSigmaYaw = s.getDouble("map_sigma_yaw_deg", p.mapSigmaYaw * 180 / M_PI) * M_PI / 180;
    const int maxHyp = s.getInt("max_hypotheses", static_cast<int>(p.maxHypotheses));
    if (!(p.independentTravel >= 0)) s.fail("independent_travel", "must be >= 0");
    if (!(p.mapSigmaXY > 0)) s.fail("map_sigma_xy", "must be > 0");
    if (!(p.mapSigmaYaw > 0)) s.fail("map_sigma_yaw_deg", "must be > 0");
    if (maxHyp < 2) s.fail("max_hypotheses", "must be >= 2");
    p.maxSigmaXY = s.getDouble("max_sigma_xy", p.maxSigmaXY);
    p.maxSigmaYaw = s.getDouble("max_sigma_yaw_deg", p.maxSigmaYaw * 180 / M_PI) * M_PI / 180;
    if (!(p.maxSigmaXY > 0) || !(p.maxSigmaYaw > 0)) s.fail("max_sigma_xy", "must be > 0");
    p.maxHypotheses = static_cast<std::size_t>(maxHyp);
    s.finish();
    return p;
}

int Relocalizer::find(int segment) const {
    while (parent_.at(segment) != segment) segment = parent_[segment];
    return segment;
}

std::pair<int, int> Relocalizer::keptAndMoved(int g1, int g2) {
    // Groups are named by their first segment: the map is 0, and the later group moves.
    return {std::min(g1, g2), std::max(g1, g2)};
}

namespace {
template <class S>
double gate(const RelocalizerParams& p) {
    return p.consistencyChi2 > 0 ? p.consistencyChi2 : S::kChi2999;
}
}  // namespace

template <class S>
void Relocalizer::accumulateStep(const Constraint& edge, double& positionVar,
                                 double& rotationVar) const {
    const typename S::Matrix c = S::covarianceOf(edge);
    constexpr int nt = S::kTranslationDof, nr = S::kDof - S::kTranslationDof;
    positionVar = c.topLeftCorner(nt, nt).trace();
    rotationVar = c.bottomRightCorner(nr, nr).trace() / nr;
}

void Relocalizer::addNode(const Graph& graph, const NodeStore& nodes, TNodeID id) {
    const NodeRecord& rec = nodes.at(id);
    const int seg = rec.segment;
    while (static_cast<int>(parent_.size()) <= seg) parent_.push_back(static_cast<int>(parent_.size()));
    const bool starts = id == 0 || segment_.back() != seg;
    double step = 0, pv = 0, rv = 0;
    if (!starts) {
        const auto e = graph.edges.find({id - 1, id});
        if (e != graph.edges.end()) {
            const auto& t = e->second.mean;
            step = params_.spatial ? std::sqrt(t.x() * t.x() + t.y() * t.y() + t.z() * t.z())
                                   : std::hypot(t.x(), t.y());
            if (params_.spatial) {
                accumulateStep<SpatialSpace>(e->second, pv, rv);
            } else {
                accumulateStep<PlanarSpace>(e->second, pv, rv);
            }
        }
    }
    segment_.push_back(seg);
    travel_.push_back(starts ? 0.0 : travel_.back() + step);
    position_var_.push_back(starts ? 0.0 : position_var_.back() + pv);
    rotation_var_.push_back(starts ? 0.0 : rotation_var_.back() + rv);
    if (starts && id > 0) {
        if (kidnaps_.empty()) {
            for (TNodeID k = 0; k < id; ++k) {
                if (find(segment_[k]) == 0) map_at_first_kidnap_.emplace_back(k, graph.nodes.at(k));
            }
        }
        KidnapRecord k;
        k.segment = seg;
        k.firstNode = id;
        k.liftTime = rec.liftTime;
        k.putDownTime = rec.putDownTime;
        kidnaps_.push_back(k);
    }
}

void Relocalizer::adoptMap(const Graph& graph, const NodeStore& nodes) {
    if (!segment_.empty()) throw std::logic_error("Relocalizer: a map is adopted before any node");
    for (TNodeID id = 0; id < nodes.size(); ++id) addNode(graph, nodes, id);
    for (auto& p : parent_) p = 0;
    kidnaps_.clear();
    map_at_first_kidnap_.clear();
}

template <class S>
typename S::Matrix Relocalizer::relativeCovariance(const Graph& graph, TNodeID i, TNodeID j,
                                                   bool moving) const {
    constexpr int nt = S::kTranslationDof, nr = S::kDof - S::kTranslationDof;
    typename S::Matrix c = S::Matrix::Zero();
    c.diagonal().head(nt).setConstant(params_.mapSigmaXY * params_.mapSigmaXY);
    c.diagonal().tail(nr).setConstant(params_.mapSigmaYaw * params_.mapSigmaYaw);
    if (!moving || segment_[i] != segment_[j]) return c;
    // Within one segment of the moved group: its odometry since the segment began, summed
    // (position variance plus the rotation's lever arm over the distance between the nodes).
    const double pv = std::abs(position_var_[j] - position_var_[i]);
    const double rv = std::abs(rotation_var_[j] - rotation_var_[i]);
    const auto& a = graph.nodes.at(i);
    const auto& b = graph.nodes.at(j);
    double d2 = (a.x() - b.x()) * (a.x() - b.x()) + (a.y() - b.y()) * (a.y() - b.y());
    if (S::kTranslationDof == 3) d2 += (a.z() - b.z()) * (a.z() - b.z());
    c.diagonal().head(nt).array() += pv / nt + rv * d2;
    c.diagonal().tail(nr).array() += rv;
    return c;
}

template <class S>
HypothesisT<S> Relocalizer::hypothesisOf(const Graph& graph, const Pending& p) const {
    HypothesisT<S> h;
    h.a = S::fromGraph(graph.nodes.at(p.a));
    h.u = S::fromGraph(graph.nodes.at(p.u));
    h.z = S::fromGraph(p.closure.constraint.mean);
    h.cov = S::covarianceOf(p.closure.constraint);
    h.uIsTo = p.uIsTo;
    return h;
}

bool Relocalizer::independent(const Pending& x, const Pending& y) const {
    if (x.closure.source != y.closure.source) return true;
    if (x.closure.matchId == y.closure.matchId) return false;
    if (segment_[x.u] != segment_[y.u]) return true;
    return std::abs(travel_[x.u] - travel_[y.u]) >= params_.independentTravel;
}

template <class S>
bool Relocalizer::consistent(const Graph& graph, const Pending& x, const Pending& y) const {
    const double chi2 = pairwiseChi2<S>(hypothesisOf<S>(graph, x), hypothesisOf<S>(graph, y),
                                        relativeCovariance<S>(graph, x.u, y.u, true),
                                        relativeCovariance<S>(graph, x.a, y.a, false));
    return chi2 <= gate<S>(params_);
}

template <class S>
bool Relocalizer::determined(const typename S::Matrix& c) const {
    constexpr int nt = S::kTranslationDof, nr = S::kDof - S::kTranslationDof;
    using Block = Eigen::MatrixXd;
    const auto largestSigma = [](const Block& m) {
        const double v = Eigen::SelfAdjointEigenSolver<Block>(m).eigenvalues().maxCoeff();
        return std::sqrt(std::max(0.0, v));
    };
    // (planar: the x, y block's larger axis and the yaw)
    return largestSigma(c.topLeftCorner(nt, nt)) <= params_.maxSigmaXY &&
           largestSigma(c.bottomRightCorner(nr, nr)) <= params_.maxSigmaYaw;
}

std::optional<Relocalizer::Merge> Relocalizer::offer(const Graph& graph, const LoopClosure& lc) {
    ++offered_;
    const int gFrom = groupOf(lc.from), gTo = groupOf(lc.to);
    if (gFrom == gTo) return std::nullopt;  // the engine's to judge, not a relocation
    const auto [kept, moved] = keptAndMoved(gFrom, gTo);
    Pending h;
    h.closure = lc;
    h.uIsTo = gTo == moved;
    h.u = h.uIsTo ? lc.to : lc.from;
    h.a = h.uIsTo ? lc.from : lc.to;
    return params_.spatial ? offerIn<SpatialSpace>(graph, h, kept, moved)
                           : offerIn<PlanarSpace>(graph, h, kept, moved);
}

template <class S>
std::optional<Relocalizer::Merge> Relocalizer::offerIn(const Graph& graph, const Pending& h,
                                                       int kept, int moved) {
    const auto samePair = [&, kept = kept, moved = moved](const Pending& p) {
        return groupOf(p.a) == kept && groupOf(p.u) == moved;
    };
    std::vector<const Pending*> agreeing;  // consistent with h
    const Pending* partner = nullptr;      // consistent and independent
    for (const auto& p : pending_) {
        if (!samePair(p) || !consistent<S>(graph, h, p)) continue;
        agreeing.push_back(&p);
        if (!partner && independent(h, p)) partner = &p;
    }
    for (auto& k : kidnaps_) {
        if (find(k.segment) == moved) ++k.hypotheses;
    }
    if (h.closure.strong || partner) {
        // The agreeing set: h, its partner, and whatever agrees with both.
        std::vector<Pending> set{h};
        if (partner) set.push_back(*partner);
        for (const Pending* p : agreeing) {
            if (p != partner && (!partner || consistent<S>(graph, *partner, *p))) set.push_back(*p);
        }
        std::vector<HypothesisT<S>> hs;
        for (const auto& p : set) hs.push_back(hypothesisOf<S>(graph, p));
        typename S::Pose T = fitTransform<S>(hs, impliedTransform<S>(hs.front()));
        // Judged at the fitted move; the verification must survive without whoever fails.
        std::vector<Pending> survivors;
        std::vector<HypothesisT<S>> keptHs;
        for (std::size_t k = 0; k < set.size(); ++k) {
            if (chi2After<S>(hs[k], T) <= gate<S>(params_)) {
                survivors.push_back(set[k]);
                keptHs.push_back(hs[k]);
            }
        }
        bool verified = false;
        for (std::size_t x = 0; x < survivors.size() && !verified; ++x) {
            verified = survivors[x].closure.strong;
            for (std::size_t y = x + 1; y < survivors.size() && !verified; ++y)
                verified = independent(survivors[x], survivors[y]);
        }
        typename S::Matrix covT = S::Matrix::Identity();
        if (verified) T = fitTransform<S>(keptHs, T, &covT);
        // Determined enough where the robot is now (the newest closure's moving end)?
        if (verified && !determined<S>(movedPoseCovariance<S>(T, covT, hs.front().u))) {
            verified = false;
            ++undetermined_;
        }
        if (verified) {
            Merge m;
            m.keptGroup = kept;
            m.movedGroup = moved;
            m.transform = S::toGraph(T);
            for (const auto& p : survivors) {
                m.accepted.push_back(p.closure);
                m.sources.insert(p.closure.source);
            }
            const auto inSet = [&](const Pending& p) {
                return std::any_of(survivors.begin(), survivors.end(), [&](const Pending& q) {
                    return q.closure.from == p.closure.from && q.closure.to == p.closure.to &&
                           q.closure.constraint.mean == p.closure.constraint.mean;
                });
            };
            // Every other pending hypothesis of the pair is judged at the move, then dropped.
            for (auto it = pending_.begin(); it != pending_.end();) {
                if (!samePair(*it)) {
                    ++it;
                    continue;
                }
                if (!inSet(*it)) {
                    if (chi2After<S>(hypothesisOf<S>(graph, *it), T) <= gate<S>(params_)) {
                        m.accepted.push_back(it->closure);
                    } else {
                        ++m.rejected;
                    }
                }
                it = pending_.erase(it);
            }
            return m;
        }
    }
    pending_.push_back(h);
    // Bounded: a group put down somewhere never mapped keeps proposing look-alikes.
    std::size_t ofPair = 0;
    for (const auto& p : pending_) ofPair += samePair(p);
    if (ofPair > params_.maxHypotheses) {
        const auto oldest = std::find_if(pending_.begin(), pending_.end(), samePair);
        pending_.erase(oldest);
        ++dropped_;
    }
    return std::nullopt;
}

void Relocalizer::commit(const Merge& m, const Graph& graph, const NodeStore& nodes) {
    ++merges_;
    rejected_total_ += m.rejected;
    const bool intoMap = m.keptGroup == 0;
    for (auto& k : kidnaps_) {
        if (find(k.segment) != m.movedGroup) continue;
        k.mergedWith = m.keptGroup;
        k.rejected += m.rejected;
        if (!intoMap || k.relocated || k.mergedLate) continue;
        // The segment's latest node: where the robot was when it found itself on the map -
        // unless the segment had ended (another kidnap) before this merge.
        TNodeID last = k.firstNode;
        for (TNodeID id = k.firstNode; id < segment_.size(); ++id) {
            if (segment_[id] == k.segment) last = id;
        }
        k.mergeTime = nodes.at(static_cast<TNodeID>(segment_.size() - 1)).timestamp;
        k.relocated = last + 1 == segment_.size();
        k.mergedLate = !k.relocated;
        k.node = last;
        k.relocationTime = nodes.at(last).timestamp;
        k.travel = travel_[last];
        k.pose = graph.nodes.at(last);
        k.sources = m.sources;
        k.agreeing = m.accepted.size();
    }
    parent_[m.movedGroup] = m.keptGroup;
}

JsonObject Relocalizer::describe() const {
    JsonObject params;
    params.set("space", params_.spatial ? "se3" : "planar")
        .set("consistency_chi2", params_.spatial ? gate<SpatialSpace>(params_) : gate<PlanarSpace>(params_))
        .set("independent_travel", params_.independentTravel)
        .set("map_sigma_xy", params_.mapSigmaXY)
        .set("map_sigma_yaw_deg", params_.mapSigmaYaw * 180 / M_PI)
        .set("max_hypotheses", params_.maxHypotheses)
        .set("max_sigma_xy", params_.maxSigmaXY)
        .set("max_sigma_yaw_deg", params_.maxSigmaYaw * 180 / M_PI);
    std::vector<JsonObject> kidnaps;
    for (const auto& k : kidnaps_) {
        std::string sources;
        for (const auto& s : k.sources) sources += (sources.empty() ? "" : "+") + s;
        JsonObject o;
        o.set("segment", k.segment)
            .set("first_node", static_cast<long long>(k.firstNode))
            .set("lift_time", k.liftTime)
            .set("put_down_time", k.putDownTime)
            .set("relocated", k.relocated)
            .set("merged_after_segment_ended", k.mergedLate)
            .set("merge_time", k.mergeTime)
            .set("merged_with_segment", k.mergedWith)
            .set("hypotheses", k.hypotheses)
            .set("rejected_hypotheses", k.rejected);
        if (k.relocated) {
            o.set("relocation_time", k.relocationTime)
                .set("travel_to_relocation_m", k.travel)
                .set("node", static_cast<long long>(k.node))
                .set("x", k.pose.x())
                .set("y", k.pose.y())
                .set("yaw", k.pose.yaw())
                .set("deciders", sources)
                .set("agreeing_closures", k.agreeing);
        }
        kidnaps.push_back(o);
    }
    JsonObject stats;
    stats.set("hypotheses_offered", offered_)
        .set("merges", merges_)
        .set("rejected_hypotheses", rejected_total_)
        .set("dropped_hypotheses", dropped_)
        .set("undetermined_merges", undetermined_)
        .set("pending_hypotheses", pending_.size());
    return JsonObject().set("params", params).set("stats", stats).set("kidnaps", kidnaps);
}

}  // namespace lodestone::graphslam::relocalization
