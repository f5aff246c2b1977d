#pragma once

#include <lodestone/graphslam/EdgeDecider.h>
#include <lodestone/graphslam/erd/magnetic/PathUncertainty.h>
#include <lodestone/graphslam/erd/magnetic/MagneticPath.h>
#include <lodestone/graphslam/erd/magnetic/TruthFunnel.h>
#include <lodestone/magnetic/BundleMatcher.h>
#include <lodestone/magnetic/FieldFeatures.h>
#include <lodestone/magnetic/FieldMapSearch.h>
#include <lodestone/magnetic/GpShiftCorrection.h>
#include <lodestone/magnetic/PlanarAlignment.h>
#include <lodestone/magnetic/SupernodeIndex.h>
#include <lodestone/magnetic/SupernodeTrack.h>

#include <deque>
#include <memory>
#include <optional>
#include <vector>

namespace lodestone::graphslam {

/** Magnetic loop closure, paper 000 §2.2-2.3. The magnetometer readings the nodes keep are
 * placed along the path (by time between their node and the previous one), resampled by
 * distance and cut into overlapping supernodes (magnetic::SupernodeTrack). Each new supernode
 * is matched by the L2 cost of eq. (2) (at the best alignment within half a stride) against
 * stored ones the robot left at least `min_travel_gap` ago: shortlisted by a KD-tree over the
 * field, and kept only where the robot can be: inside a chi-square gate of the pose
 * uncertainty since the last closure (closure::PathUncertainty; across a kidnap, everywhere).
 * Chains of consistent matches form node bundles (magnetic::BundleMatcher). Bundles whose
 * targets lie at different places inside the gate are told apart by likelihood: each place's
 * best bundle is slid along its path by the GP, and the place that fits by a likelihood ratio
 * of `ambiguity_log_ratio` over every other wins; otherwise the match is ambiguous and
 * dropped. The last `gp_window` metres of a bundle are aligned along the path by the GP
 * correction of eq. (3) and, if the field fits (normalized residual under
 * `max_normalized_rms`), subdivided into node-to-node edges (§2.3): every `edge_every`-th
 * query node gets an edge from the target node at its corrected travel, with the along-track
 * sigma of the GP scan and loose cross-track and heading sigmas (a field sequence says where
 * along a path the robot is, little about across it); or, with `alignment = plane`, moved in
 * the plane against every earlier pass found there (MagneticGpERDAlignment.cpp).
 * Where no sequence match places the robot - it walks beside earlier passes, not on them - the
 * field map does (`map_search`, MagneticGpERDFieldMap.cpp): every `map_search_every` metres the
 * last `map_window` metres of readings are placed against a 2-D GP of every earlier reading
 * near where the graph has them (magnetic::FieldMapSearch). The map is the readings anchored
 * to their nodes, so it moves with the graph.
 * NaN, infinite or saturated readings are dropped and counted. INI section [MagneticGpERD]. */
class MagneticGpERD : public EdgeDecider {
  public:
    struct Params {
        magnetic::FieldMode mode{magnetic::FieldMode::Invariant};
        std::string sensorLabel;    ///< only this magnetometer ("": the first one seen)
        double saturation{1000.0};  ///< [uT] a component this large is a saturated reading
        magnetic::SupernodeTrack::Params track;
        int indexBins{8};
        std::size_t candidates{20};   ///< KD-tree shortlist per supernode
        double maxCost{1.5};          ///< [uT] RMS, eq. (2) per element
        double minSpread{1.0};        ///< [uT] a supernode flatter than this matches nothing
        double minTravelGap{4.0};     ///< [m]
        /** Position gate: a stored supernode is a candidate only if its end lies within this
         * chi-square (2 dof) of the query's end under the pose uncertainty since the last
         * closure (closure::PathUncertainty). 11.83: 99.73 %, "3 sigma". */
        double gateChi2{11.83};
        closure::PathUncertainty::Params uncertainty;
        double sameplaceRadius{1.5};  ///< [m] bundles whose targets are this close agree
        /** Bundles at different places inside the gate: the place whose best bundle the GP
         * fits best (all scored on the same query readings) wins if its log-likelihood beats
         * every other's by this much, deflated by the fit's dispersion (normalized RMS^2 when
         * over 1); else none does. Two copies of one field differ by up to 7 from resampling
         * alone (the unit tests), and the test is repeated at every supernode: 10. */
        double ambiguityLogRatio{10.0};
        magnetic::BundleMatcher::Params bundle;
        double gpWindow{3.0};  ///< [m] of query path aligned by the GP
        magnetic::GpHyperparameters gp{3.0, 0.28, 0.15, 10.0};  // lodestone-magfit on the Kok walks
        magnetic::ShiftScanParams shift;
        double maxNormalizedRms{2.0};
        /** path: paper 000 eq. (3), the query slid along the target's path (across it the
         * edges stay loose); plane: then moved in the plane against a 2-D GP of every earlier
         * pass the bundles found there (PlanarAlignment), which also corrects across and pins
         * the heading - what a relocation needs; measured, its sideways correction is also
         * wrong too often on walks beside earlier passes, so the magnetic-only INIs use path
         * (README: the magnetic results). */
        enum class Alignment { Path, Plane } alignment{Alignment::Plane};
        magnetic::PlanarAlignmentParams plane;
        double planeMargin{0.5};  ///< [m] of target path either side of the query window
        int planeSubsample{2};    ///< every n-th target reading into the 2-D GP
        /** The field map (MagneticGpERDFieldMap.cpp). */
        struct FieldMap {
            bool enabled{false};  // opt-in: README "The field map" (measured)
            double every{1.0};       ///< [m] of travel between searches
            double window{3.0};      ///< [m] of query path placed
            int maxPoints{250};      ///< earlier readings in the local GP (thinned beyond)
            /** [uT] how well readings repeat between passes of one place - the map's noise.
             * Along one pass (what lodestone-magfit fits) a hand-held magnetometer is smooth
             * to 0.15 uT, but its passes of one place differ by about 1 uT (device height and
             * tilt; README: the field map on the Kok walks). <= 0: gp_sigma_n. */
            double sigmaN{0};
            magnetic::FieldMapSearchParams search;
        } fieldMap;
        int edgeEvery{3};                  ///< [nodes]
        double sigmaAlong{0.03};           ///< [m] floor, added to the GP's shift sigma
        /** An alignment's edges share its one error (the shift, the pass's offset across, its
         * heading): each edge's covariance is multiplied by their number, so together they
         * carry the alignment's information once. false: each edge as sure as the whole
         * alignment (paper 000 §2.3's subdivision), which the graph sums as independent. */
        bool edgesShareAlignment{false};
        double sigmaCross{0.20};           ///< [m]
        double sigmaYaw{10 * M_PI / 180};  ///< [rad]
    };

    /** One accepted bundle alignment and the edges it gave. */
    struct Record {
        std::size_t querySupernode{0};
        double offset{0}, shift{0}, shiftSigma{0}, normalizedRms{0}, cost{0};
        bool plane{false};     ///< refined in the plane
        bool fieldMap{false};  ///< placed by the field map, no sequence match
        double logRatio{0};    ///< field map: joint log-likelihood over the map's prior
        Eigen::Vector3d planeDelta{Eigen::Vector3d::Zero()};
        std::vector<std::pair<TNodeID, TNodeID>> edges;  ///< (target node, query node)
        std::vector<Constraint> constraints;
        /** Edges made by the alignment, registered together once it is complete. */
        struct PendingEdge {
            TNodeID target{0};
            std::size_t queryNode{0};
            mrpt::poses::CPose2D mean;
            Eigen::Matrix2d positionCov{Eigen::Matrix2d::Zero()};
            double yawVariance{0};
        };
        std::vector<PendingEdge> pending;
    };
    struct Stats {
        std::size_t supernodes{0}, flatSupernodes{0}, matchedSupernodes{0}, gatedOut{0}, bundles{0}, ambiguous{0},
            resolved{0}, gpRejected{0}, alignments{0}, edges{0}, planeRejected{0};
        /** Field-map searches and what became of them. */
        std::size_t mapSearches{0}, mapGateTooWide{0}, mapNoMap{0}, mapNoFit{0}, mapNotAboveNull{0},
            mapAmbiguous{0}, mapTooLoose{0}, mapAccepted{0};
        std::vector<double> queryMs;  ///< per supernode: search + bundle + GP [ms]
    };

    MagneticGpERD();
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    const Params& params() const { return params_; }
    bool updateState(mrpt::obs::CActionCollection::Ptr action,
                     mrpt::obs::CSensoryFrame::Ptr observations,
                     mrpt::obs::CObservation::Ptr observation) override;
    std::set<std::string> requiredObservations() const override {
        return {"CObservationMagnetometer"};
    }
    JsonObject describe() const override;
    /** Pins its path where any closer's kept closure placed a node (MagneticPath::pinKept). */
    void closuresKept(const std::vector<LoopClosure>& kept) override {
        path_.pinKept(kept, *m_graph);
    }

    const std::vector<Record>& records() const { return records_; }
    const Stats& stats() const { return stats_; }

    /** With the run's true trajectory (SlamComponent::setDiagnosticTruth): for every new
     * supernode whose end truly revisits an earlier place, the stage that place's supernode
     * reached (MagneticGpERDFunnel.cpp); `stage` indexes these. */
    enum class TruthStage {
        Flat,            ///< the query supernode was flat (min_spread)
        Reverse,         ///< the place was walked the other way: no code path compares that
        NotShortlisted,  ///< not among the KD-tree's `candidates` nearest in field space
        OutsideGate,     ///< outside the position gate
        CostTooHigh,     ///< eq. (2) cost over max_cost
        NoBundle,        ///< no bundle ends there (min_chain consistent matches)
        GpRejected,      ///< the GP alignment did not fit
        Ambiguous,       ///< another place as likely
        LostToOther,     ///< another place's bundle was chosen
        Aligned          ///< aligned there, edges made
    };
    static const char* toString(TruthStage stage);
    const std::vector<FunnelRecord>& funnel() const { return funnel_; }
    const magnetic::SupernodeTrack& track() const { return *track_; }

  private:
    void rebuild();
    void onNode(TNodeID id);
    void query(const magnetic::Supernode& q);
    /** What a query came to, for the diagnostics (only kept with a diagnostic truth). */
    struct Trace {
        bool flat{false};
        std::vector<std::size_t> shortlist;  ///< the KD-tree's, before the gate
        std::vector<std::vector<magnetic::BundleMatch>> places;
        enum class Outcome { None, GpRejected, Ambiguous, Aligned } outcome{Outcome::None};
        std::size_t chosen{0};  ///< the place aligned (Aligned)
        bool edges{false};
    };
    void diagnose(const magnetic::Supernode& q, const Trace& trace);
    /** Query samples [qBegin, end of the bundle) slid along its target's path (eq. 3). */
    struct PathFit {
        std::size_t qBegin{0}, qEnd{0};  ///< query samples [qBegin, qEnd)
        magnetic::ShiftResult shift;
    };
    /** The first query sample of a bundle's window: its last `gp_window` metres, within the
     * chain. */
    std::size_t windowStart(const magnetic::BundleMatch& b) const;
    std::optional<PathFit> fitAlongPath(const magnetic::BundleMatch& b, std::size_t qBegin) const;
    /** Bundles (cheapest first) grouped by where their targets lie in the graph. */
    std::vector<std::vector<magnetic::BundleMatch>> groupByPlace(
        const std::vector<magnetic::BundleMatch>& bundles) const;
    /** One place's bundles (cheapest first) aligned: edges if the field fits. */
    void align(const std::vector<magnetic::BundleMatch>& bundles, const PathFit& fit);
    /** §2.3 along the path: the bundle subdivided into node-to-node edges on the target's path. */
    void addPathEdges(const magnetic::BundleMatch& b, std::size_t qBegin, std::size_t qEnd,
                      const magnetic::ShiftResult& shift, Record& rec);
    /** One closure edge target -> queryNode, planar, pending in `rec` until commitEdges. */
    void addEdge(TNodeID target, std::size_t queryNode, const mrpt::poses::CPose2D& mean,
                 const Eigen::Matrix2d& positionCov, double yawVariance, Record& rec);
    /** The alignment's pending edges registered as closures (edges_share_alignment: each with
     * its covariance times their number) and `rec` kept when it made any. */
    void commitEdges(Record& rec);
    /** Plane refinement of an along-the-path alignment, then its edges; false when it does not
     * fit. */
    bool alignInPlane(const std::vector<magnetic::BundleMatch>& bundles, std::size_t qBegin,
                      std::size_t qEnd, double shift, Record& rec);
    /** Query node `qn` moved to `moved0` (before `r`), its heading turned by `turn` and then by
     * r's: an edge from `target`, with r's covariance at that node's lever arm. */
    void addMovedNodeEdge(std::size_t qn, TNodeID target, const Eigen::Vector2d& moved0, double turn,
                          const magnetic::PlanarAlignmentResult& r, Record& rec);
    /** The field map's search for the stretch ending with supernode `q`. */
    void matchFieldMap(const magnetic::Supernode& q);
    /** An accepted field-map match as edges: each query node from `qBegin`'s to `qNode` moved
     * as its readings were, tied to the nearest node of the map readings `mapReadings`. */
    void addFieldMapEdges(const magnetic::Supernode& q, const magnetic::FieldMapMatch& match,
                          std::size_t qBegin, std::size_t qNode,
                          const std::vector<std::size_t>& mapReadings);
    void countVerdict(magnetic::FieldMapVerdict v);
    bool positionAtTravel(double s, int segment, Eigen::Vector2d& p) const;
    bool nodeAtTravel(double s, int segment, TNodeID& k, double& frac) const;
    mrpt::math::TPoint2D positionOf(TNodeID id) const;

    Params params_;
    std::unique_ptr<magnetic::SupernodeTrack> track_;
    std::unique_ptr<magnetic::SupernodeIndex> index_;
    std::unique_ptr<magnetic::BundleMatcher> matcher_;
    MagneticPath path_;              // travel, segment, pose uncertainty per node
    std::vector<bool> constrained_;  // per node: has a magnetic edge already
    std::optional<std::size_t> previous_supernode_;
    std::deque<std::size_t> unindexed_;  // supernodes too recent to be matched yet
    TNodeID seen_{0};
    double last_map_search_{-1e18};  // [m] travel at the last field-map search
    std::vector<Record> records_;
    Stats stats_;
    std::vector<FunnelRecord> funnel_;
};

}  // namespace lodestone::graphslam
