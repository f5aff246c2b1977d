#pragma once

#include <lodestone/graphslam/NodeStore.h>
#include <lodestone/graphslam/gso/PoseGraphSolver.h>
#include <lodestone/graphslam/ReportJson.h>
#include <lodestone/graphslam/relocalization/ClosureAlgebra.h>
#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <deque>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace lodestone::graphslam::relocalization {

/** What Relocalizer reads from [relocalization]. */
struct RelocalizerParams {
    /** Hypotheses in SE(3) (a hand-held camera's graph, `[CeresGSO] mode = se3`) rather than
     * x, y, yaw: set by the engine from its optimizer, not read from the INI. */
    bool spatial{false};
    double consistencyChi2{0};  ///< 0: chi-square 99.9 % for the space's degrees of freedom
    double independentTravel{1.0};    ///< [m]
    double mapSigmaXY{0.05};          ///< [m] relative pose of two nodes of one group ...
    double mapSigmaYaw{M_PI / 180};   ///< [rad] ... once merged or optimized (per rotation axis)
    std::size_t maxHypotheses{400};   ///< pending per pair of groups (oldest dropped)
    /** The agreeing closures must pin the moved group's latest pose down this well (1 sigma of
     * the fitted move): closures along one straight line may agree and still leave the heading
     * free (magnetic ones claim 10 deg), and a heading error swings the whole segment. The
     * defaults make a merge right (0.5 m, 10 deg) at the 99.73 % quantile of its own fit:
     * 0.5 / sqrt(11.83) (chi-square, 2 dof) and 10 deg / sqrt(9.0) (1 dof). */
    double maxSigmaXY{0.145};              ///< [m] (SE(3): in any direction)
    double maxSigmaYaw{3.3 * M_PI / 180};  ///< [rad] (SE(3): about any axis)
};

/** Global relocalization after a kidnap, keeping the map intact (paper 000 §2.4).
 *
 * Segments (continuous odometry between kidnaps) form groups: segment 0's group is the map;
 * each kidnap opens a group of its own that keeps mapping in its own frame (as ORB-SLAM3's
 * Atlas) until a verified match merges it. A loop closure joining two groups is not an edge
 * yet: it is a hypothesis of where the moved group lies (the later one, or the one that is not
 * the map). A merge needs verification:
 *  - two hypotheses that are pairwise consistent (their implied moves agree within the
 *    chi-square gate of their claimed covariances plus the moved group's odometry between
 *    their ends) and independent (different matchers, or the same matcher at query nodes at
 *    least `independent_travel` apart along the segment and from different matches); or
 *  - one hypothesis its matcher marked strong (evidence over that matcher's INI threshold).
 * The move is then fitted to the agreeing hypotheses; each is judged at it (a wrong one is
 * dropped), and the fit must pin the moved group's pose down (`max_sigma_xy`,
 * `max_sigma_yaw_deg`), else the hypotheses wait for more; every other pending hypothesis of
 * the pair is judged at the move; only those that agree become edges. The kept group never moves: only the moved group's nodes change, rigidly.
 *
 * The same in SE(3) for a hand-held camera's graph (Params::spatial, ClosureAlgebra's
 * SpatialSpace), where a segment's move has a height, pitch and roll too.
 *
 * INI section [relocalization]: consistency_chi2 (0: chi-square 99.9 % for 3 dof, 6 in SE(3)),
 * independent_travel [m], map_sigma_xy [m], map_sigma_yaw_deg, max_hypotheses, max_sigma_xy [m],
 * max_sigma_yaw_deg. */
class Relocalizer {
  public:
    using Params = RelocalizerParams;
    static Params readParams(const mrpt::config::CConfigFileBase& ini);

    /** What one kidnap (a segment after the first) became. */
    struct KidnapRecord {
        int segment{0};
        TNodeID firstNode{0};
        double liftTime{NAN}, putDownTime{NAN};  ///< [s] from the node decider, if it knows
        bool relocated{false};  ///< joined the map while the robot was still in the segment
        /** Joined the map only after the segment had ended (a later kidnap), through a later
         * pass of the map by its places: the robot was never relocated while in it. */
        bool mergedLate{false};
        double mergeTime{NAN};  ///< [s] data time of the merge (either kind)
        double relocationTime{NAN};              ///< [s] timestamp of `node`
        double travel{0};      ///< [m] the segment's odometry from its start to `node`
        TNodeID node{0};       ///< the segment's latest node when it joined the map
        mrpt::poses::CPose3D pose;  ///< that node's pose once the merged group was solved
        std::set<std::string> sources;  ///< matchers of the agreeing hypotheses
        std::size_t agreeing{0}, hypotheses{0}, rejected{0};
        int mergedWith{-1};    ///< the first segment of the group it was merged into
    };

    /** A verified merge, for the engine to apply: move every node of `movedGroup` by
     * `transform` (left-composed; planar in a planar graph), then add `accepted` as loop
     * closures. */
    struct Merge {
        int movedGroup{0}, keptGroup{0};  ///< groups by their first segment
        mrpt::poses::CPose3D transform;
        std::vector<LoopClosure> accepted;
        std::size_t rejected{0};
        std::set<std::string> sources;
    };

    explicit Relocalizer(Params p = {}) : params_(p) {}
    const Params& params() const { return params_; }

    /** A node just registered (IDs in order). */
    void addNode(const Graph& graph, const NodeStore& nodes, TNodeID id);
    /** Every node the store holds now is a loaded map's: one group, the map (whatever segments
     * it was made of), and none of its segment starts a kidnap of this run. Before any other
     * node is added. */
    void adoptMap(const Graph& graph, const NodeStore& nodes);
    /** The group (its first segment) a node belongs to; 0 is the map. */
    int groupOf(TNodeID id) const { return find(segment_.at(id)); }
    bool sameGroup(TNodeID a, TNodeID b) const { return groupOf(a) == groupOf(b); }
    /** The group of a segment (one not seen yet: its own). */
    int groupOfSegment(int segment) const {
        return segment >= 0 && segment < static_cast<int>(parent_.size()) ? find(segment) : segment;
    }
    /** A closure joining two groups (not in the graph): kept as a hypothesis; returns the
     * merge it completes, if any. */
    std::optional<Merge> offer(const Graph& graph, const LoopClosure& lc);
    /** The engine applied `m` to the graph: the groups become one; kidnap records are filled. */
    void commit(const Merge& m, const Graph& graph, const NodeStore& nodes);

    const std::vector<KidnapRecord>& kidnaps() const { return kidnaps_; }
    /** Map nodes (segment 0) as they were when the first kidnap started: the reference for
     * what relocations did to the map. */
    const std::vector<std::pair<TNodeID, mrpt::poses::CPose3D>>& mapAtFirstKidnap() const {
        return map_at_first_kidnap_;
    }
    JsonObject describe() const;

  private:
    struct Pending {
        LoopClosure closure;
        TNodeID a{0}, u{0};  // anchored end, moving end
        bool uIsTo{true};
    };
    int find(int segment) const;
    /** Which of two groups moves: the one that is not the map, else the later one. */
    static std::pair<int, int> keptAndMoved(int g1, int g2);
    bool independent(const Pending& x, const Pending& y) const;
    // In the graph's pose space S (ClosureSpace.h):
    template <class S>
    std::optional<Merge> offerIn(const Graph& graph, const Pending& h, int kept, int moved);
    template <class S>
    HypothesisT<S> hypothesisOf(const Graph& graph, const Pending& p) const;
    template <class S>
    typename S::Matrix relativeCovariance(const Graph& graph, TNodeID i, TNodeID j,
                                          bool moving) const;
    template <class S>
    bool consistent(const Graph& graph, const Pending& x, const Pending& y) const;
    /** The fitted move pins the moved group's pose `c` (its covariance) down well enough. */
    template <class S>
    bool determined(const typename S::Matrix& c) const;
    template <class S>
    void accumulateStep(const Constraint& edge, double& positionVar, double& rotationVar) const;

    Params params_;
    std::vector<int> segment_;        // per node
    std::vector<double> travel_;      // per node, along its segment [m]
    // per node, odometry variance sums in the segment: position (trace), rotation (per axis)
    std::vector<double> position_var_, rotation_var_;
    std::vector<int> parent_;         // union-find over segments
    std::deque<Pending> pending_;
    std::vector<KidnapRecord> kidnaps_;
    std::vector<std::pair<TNodeID, mrpt::poses::CPose3D>> map_at_first_kidnap_;
    std::size_t offered_{0}, merges_{0}, rejected_total_{0}, dropped_{0}, undetermined_{0};
};

}  // namespace lodestone::graphslam::relocalization
