#pragma once

#include <lodestone/graphslam/EdgeDecider.h>
#include <lodestone/graphslam/erd/magnetic/MagneticPath.h>
#include <lodestone/graphslam/erd/magnetic/PathUncertainty.h>
#include <lodestone/magnetic/PassNoiseEstimate.h>
#include <lodestone/magnetic/SupernodeTrack.h>
#include <lodestone/magnetic/WindowComparison.h>
#include <lodestone/magnetic/WindowDisplacement.h>

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

namespace lodestone::graphslam {

/** Magnetic loop closure by short windows of the field, after Kok & Solin, "Online
 * One-Dimensional Magnetic Field SLAM with Loop-Closure Detection" (MFI 2024): the last
 * `window_length` metres of readings, in the levelled robot frame (heading-aligned), compared
 * with every earlier window both ways - walked again the same way (forward) and walked back
 * (the sequence reversed; the horizontal components turned by the relative heading, which the
 * field itself measures) - weighted by a Gaussian position prior from the pose uncertainty.
 * Every threshold is a quantile of the noise model: the readings of one place repeat between
 * passes as magnetic::PassNoise says (white noise, an offset and a trend over the window), the
 * position prior is closure::PathUncertainty.
 *   - excitation: a window whose field is flat within the noise (chi-square, 3(n-1) dof) never
 *     closes - it would match anywhere;
 *   - gate: a target is a candidate only where the robot can be (chi-square, 2 dof, of the
 *     pose uncertainty relative to the target: closure::PathUncertainty::relativeGateDistance2;
 *     across a kidnap, everywhere);
 *   - distance (pass_displacement): how far beside the earlier pass this one ran, weighed by
 *     magnetic::WindowDisplacementModel - near (close enough to place the robot within
 *     `distinct_radius`) or beside it;
 *   - fit: the best candidate's differences must be noise (chi-square, 3n dof; with
 *     pass_displacement, at the near distance);
 *   - distinct: the posterior of the best place (candidates within `distinct_radius` of it
 *     are the same place, on any earlier pass, passed near) against every other candidate in
 *     the gate, every pass beside, and the null hypothesis - no earlier place: the window
 *     differs from each candidate as two unrelated stretches of a field as lively as this
 *     window's do (the window's own spread) - must reach
 *     `min_posterior`. Each candidate's weight is its likelihood ratio over the null times its
 *     position prior normalized over the candidates, so a wide gate (many places to be
 *     fooled by) asks for more evidence. A look-alike elsewhere, a field too smooth to say
 *     where along the path, or too little field for the gate's size leaves it undecided.
 * An accepted window gives one node-to-node edge: the query node on the target's path,
 * its heading turned by the field's relative heading, along-track sigma from the fit's
 * curvature (and what the passes' distance does to it), across-track `sigma_cross`. INI
 * section [MagneticWindowERD]. */
class MagneticWindowERD : public EdgeDecider {
  public:
    struct Params {
        std::string sensorLabel;  ///< the magnetometer queried ("": the first one seen)
        /** Walked back, a magnetometer mounted off the robot's centre line passes where its
         * mirror image (the same mounting, the other side) passed on the way out: backward
         * windows are compared with that sensor's readings when the robot carries one. */
        bool mirrorSensors{true};
        double saturation{1000.0};  ///< [uT] a component this large is a saturated reading
        double step{0.05};          ///< [m] readings resampled by travel
        double window{2.0};      ///< [m] of path per window (Kok & Solin: ~1 s of walking; README)
        double queryEvery{0.1};  ///< [m] of travel between queries
        /** A query whose place falls short of min_posterior for want of field gathers the
         * windows before it, in sequence: every candidate's place is followed back along its
         * own path through up to `chain_windows` - 1 earlier windows of the query (each
         * `window_length`, not overlapping), each aligned again within what the passes'
         * distance through that window's turn allows, and their evidence (near and beside,
         * against the null of unrelated places) is added to its own. Where the field is quiet
         * the closer decides on more of it. 1: each window alone. */
        int chainWindows{1};
        /** Learn the pass noise from the run's own matches (magnetic::PassNoiseEstimate):
         * `window_sigma` is then the prior, worth `noise_prior_windows` windows of readings,
         * and each closed window's differences (windows not overlapping) update it; the
         * tests follow the estimate. With chain_windows, windows are chained only once the
         * matches outweigh the prior (a chain adds up whatever the noise model gets wrong). */
        bool learnNoise{false};
        double noisePriorWindows{1.0};
        /** How the readings of one place differ between two passes (magnetic::PassNoise):
         * white noise of `window_sigma` [uT] per component, plus over a window an offset of
         * `window_bias_sigma` [uT] and a trend of `window_trend_sigma` [uT/m]. (`step` is
         * resample_step.) */
        magnetic::PassNoise noise;
        /** [m] the field's correlation length along a path (lodestone-magfit's fit): with
         * the query window's own spread, how two unrelated stretches differ - the null
         * hypothesis every candidate must beat. */
        double lengthScale{0.28};
        /** How the null hypothesis - no earlier place in the gate - reads the query window.
         * Window: as two unrelated stretches of a field as lively as the query window (its own
         * spread) differ; a quiet window then looks as much like any quiet stretch as like its
         * own place, and never closes. Building: the query window read at a place of the
         * building outside the gate taken at random - its likelihood averaged over the path's
         * windows there, a length scale apart (MagneticWindowNull.cpp): a quiet window at a
         * level few places share is evidence, one at the building's usual level is not. */
        enum class NullModel { Window, Building };
        NullModel nullModel{NullModel::Window};
        double nullOdds{1.0};  ///< prior odds of "no earlier place" against "one of the candidates"
        double minTravelGap{4.0};  ///< [m] targets the robot left at least this long ago
        double gateChi2{11.83};    ///< 2 dof, 99.73 %
        closure::PathUncertainty::Params uncertainty;
        double quantile{0.9973};  ///< of the excitation and fit tests
        double minPosterior{0.9973};
        double distinctRadius{0.5};  ///< [m]
        double closureEvery{0.5};    ///< [m] of query travel between closures
        /** An accepted window closes only once a later window that does not overlap it (an
         * independent stretch of the field, `window_length` on) is accepted and places the
         * robot consistently (within distinct_radius); after that the match continues with
         * every agreeing window. A chance look-alike seldom repeats on the next stretch. */
        bool confirm{false};
        /** Two passes of one place run beside each other by a distance whose prior is
         * half-normal with `sigma_cross`; the field says how far
         * (magnetic::WindowDisplacementModel). A place is the same when the passes ran close
         * enough to place the robot within `distinct_radius` (nearRadius): the fit test takes
         * the differences at that distance, a candidate further apart counts against its
         * place, and the closure's across-track sigma is the distance's posterior. false: the
         * same place means the same line (C1 alone), the across-track sigma is `sigma_cross`. */
        bool passDisplacement{true};
        /** With pass_displacement: passes beside each other differ by the field's fine part
         * only - its amplitude measured in the query window from readings `gp_length_scale`
         * apart - while unrelated places differ by the window's whole spread (a broad part
         * that passes a metre apart still share). false: one amplitude, the spread, for both. */
        bool fineAmplitude{false};
        /** [m] a loaded map's reading is not a target when an earlier pass of the map runs
         * within this of it, both its windows' lengths before and after (within twice this):
         * a map holds each line of the floor once, not once per session that walked it.
         * Two lines 0.1 m apart differ by 2 sf^2 (1 - exp(-r^2 / 2 l^2)) = 0.12 sf^2 at
         * l = 0.28 m: under the reading noise (window_sigma = 1 uT) for a field spread sf up to
         * 2.9 uT. 0: every map reading is a target. */
        double mapThinningRadius{0.1};
        double sigmaAlongFloor{0.03};  ///< [m]
        double sigmaCross{0.20};       ///< [m]
        double turnFloorDeg{2.0};      ///< [deg] added to the field's turn sigma
    };
    /** What became of the queries (the funnel of this decider). */
    struct Stats {
        std::size_t queries{0}, flat{0}, noCandidate{0}, noFit{0}, ambiguous{0}, accepted{0},
            unmeasured{0}, confirmed{0}, forward{0}, backward{0}, edges{0};
        /** Queries that gathered earlier windows (chain_windows), and of them those accepted. */
        std::size_t chained{0}, chainedAccepted{0};
        std::size_t noiseUpdates{0};  ///< (learn_noise) times the tests took a new estimate
        std::size_t mapReadings{0}, mapReadingsThinned{0};  ///< of a loaded map (thinMap)
        std::vector<double> queryMs;
    };

    /** With the run's true trajectory (SlamComponent::setDiagnosticTruth): for every query
     * whose newest reading revisits an earlier place (within `distinct_radius` of it, at least
     * `min_travel_gap` of travel later), how far the true place got through the tests. */
    enum class TruthStage {
        Flat,         ///< the query window was flat
        NoWindow,     ///< the true place has no whole window that way (a segment's start or end)
        OutsideGate,  ///< the true place lay outside the position gate
        NoFit,        ///< its differences were not noise (fit test)
        LostToOther,  ///< another place fitted best
        Ambiguous,    ///< it fitted best, short of min_posterior
        Accepted,     ///< accepted, no edge (closure_every)
        Closed        ///< an edge was made
    };
    static const char* toString(TruthStage stage);
    struct TruthQuery {
        TNodeID queryNode{0};
        TruthStage stage{TruthStage::Flat};
        bool backward{false};  ///< the true place walked the other way
        double gate2{NAN};     ///< the true place's squared Mahalanobis distance in the gate
        double fitChi2{NAN};
    };

    MagneticWindowERD();
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
    const Stats& stats() const { return stats_; }
    const std::vector<TruthQuery>& truthQueries() const { return truth_queries_; }

  private:
    /** The best fit of one stored sample as the query's newest reading's place. */
    struct Candidate {
        const magnetic::SupernodeTrack* track{nullptr};  ///< whose readings `sample` indexes
        std::size_t sample{0};
        magnetic::WindowDirection direction{magnetic::WindowDirection::Forward};
        magnetic::WindowFit fit;
        Eigen::Vector2d position{0, 0};  ///< the sample's place in the graph
        double gate2{0};                 ///< position prior's squared Mahalanobis distance
        /** -2 log of its weight up to a constant: the best candidate has the least. Same line:
         * fit.chi2 + gate2; with pass_displacement: -2 (logNear + position and turn prior). */
        double total{0};
        double fitStat{0};  ///< the fit test's chi-square (fit.chi2, or at distinct_radius apart)
        double logWeight{-INFINITY};  ///< log of its posterior weight: its place within reach
        double logFar{-INFINITY};     ///< ... and its place beside, passed further apart
        double nearDelta2{0};         ///< [m^2] the passes' squared distance, posterior
        double logUnrelated{0};       ///< Evidence::logUnrelated of its differences
    };
    /** A candidate's prior: the gate's squared Mahalanobis distance, the graph's relative
     * heading and its variance (across a kidnap: 0, 0, infinite). */
    struct Prior {
        Eigen::Vector2d position{0, 0};  ///< the target sample's place in the graph
        double gate2{0}, turn{0}, turnVariance{INFINITY};
    };
    /** What a query came to, for the diagnostics. */
    struct Outcome {
        bool flat{false}, closed{false};
        std::optional<Candidate> best;
        double posterior{NAN};
        std::optional<magnetic::WindowDisplacementModel> displacement;  ///< pass_displacement
    };
    void rebuild();
    void onNode(TNodeID id);
    void query(std::size_t first);
    /** The earlier windows' evidence added to every candidate within reach of the best, up to
     * chain_windows, then `decided` asked once on the whole chain (MagneticWindowChain.cpp);
     * false when there was no earlier window. With a building null (`firstNull` finite: the
     * query window's) each earlier window is weighed against the building's windows too
     * (its own buildingNull), as if its place were drawn afresh. */
    bool chainEvidence(std::vector<Candidate>& all, std::size_t first,
                       const std::function<bool()>& decided, double firstNull) const;
    struct ChainWindow;
    struct ChainStep;
    /** Candidate `k`, whose window started at `from` in its track, followed one window back:
     * the earlier window realigned within the tolerance (MagneticWindowChain.cpp). */
    ChainStep followBack(const Candidate& k, long from, ChainWindow& window) const;
    /** (learn_noise) A closed window's differences into the pass noise estimate; the tests
     * take the estimate once it moved by a tenth (MagneticWindowNoise.cpp). */
    void learnNoise(const Candidate& best, std::size_t first);
    /** (learn_noise) The run's matches outweigh the prior: the noise is the run's own. */
    bool noiseLearnt() const;
    /** Whether the stretch of windows a chain would gather before the query's (in its segment)
     * is flat in the heading-free channels (a window flat alone is then queried only where the
     * noise is learnt: MagneticWindowNoise.cpp). */
    bool stretchFlat(std::size_t first) const;
    /** The displacement model's basis for the current noise, and what was projected in it. */
    void rebuildBasis();
    /** (null_model = building) log of the query window's likelihood at a place of the path
     * outside the gate taken at random, on the footing of Evidence::logNear + logUnrelated;
     * NaN while too little of the path lies outside the gate (MagneticWindowNull.cpp). */
    double buildingNull(std::size_t first, const magnetic::WindowDisplacementModel& model) const;
    /** (null_model = building) Candidates weighed with logNull = 0 put against buildingNull,
     * or against unrelated places of the model while the path is too short for it; returns
     * the null used (NaN: the model's). */
    double weighAgainstBuilding(std::vector<Candidate>& all, std::size_t first,
                                const magnetic::WindowDisplacementModel& model) const;
    /** The tests on a query's candidates (fit, posterior), then its closure. */
    void decide(std::size_t first, double excitation, std::vector<Candidate>& candidates,
                Outcome& out);
    Prior priorAt(const magnetic::SupernodeTrack& track, std::size_t c, TNodeID qNode,
                  const Eigen::Vector2d& here) const;
    /** A lower bound of priorAt's gate distance for every sample of `sample`'s node (0 across
     * a kidnap): the gate's least distance to the node's interval. */
    double nodeGateBound(const magnetic::TrackSample& sample, TNodeID qNode,
                         const Eigen::Vector2d& here) const;
    /** The truth's stage for the query ending at `first` + n - 1 (MagneticWindowFunnel.cpp). */
    std::optional<std::size_t> diagnose(std::size_t first, const Outcome& out);
    JsonObject describeTruth() const;
    /** The fit of stored sample `c` of `track` as the place of the query's newest reading,
     * `direction`, if its window is whole there. */
    void compareAt(const magnetic::SupernodeTrack& track, std::size_t c,
                   magnetic::WindowDirection direction, std::size_t first, const Prior& prior,
                   std::vector<Candidate>& out) const;
    /** The field's spread in the query window, the reading noise taken out (from its
     * excitation): the amplitude of the null and displacement models. */
    double windowSpread(double excitation) const;
    /** The same in the map's frame (each reading's horizontal part turned by the graph's
     * heading there): the field's own variation over the window, without the turning of the
     * robot-frame components that a turn in a uniform field shows. */
    double mapFrameSpread(std::size_t first) const;
    /** The query window's excitation in the map's frame (squared deviations from its mean over
     * the reading noise and the heading's interpolation within a node interval), as
     * magnetic::windowExcitation in the robot's. */
    double mapFrameExcitation(std::size_t first) const;
    /** A stored reading a query at `queryTravel` may be compared with: min_travel_gap behind
     * it, or a loaded map's. */
    bool leftBehind(const magnetic::TrackSample& stored, double queryTravel) const;
    /** The query window's readings, each horizontal part turned by the graph's heading. */
    std::vector<Eigen::Vector3d> mapFrameWindow(std::size_t first) const;
    /** The amplitude of the field's fine part in the query window (fine_amplitude): from the
     * mean square difference of readings gp_length_scale apart, 2 sigma^2 (1 - exp(-1/2)) for
     * the squared-exponential kernel; the smaller of the robot and map frames' (as the spread). */
    double fineAmplitude(std::size_t first) const;
    /** log of the position prior's normalizer over the candidates. */
    static double logPriorNormalizer(const std::vector<Candidate>& all);
    /** With pass_displacement: every candidate's weight near and far, its total and fitStat;
     * against `logNull` (buildingNull) where finite, else the model's unrelated places. */
    void weighDisplaced(std::vector<Candidate>& all, std::size_t first,
                        const magnetic::WindowDisplacementModel& model, double logNull) const;
    /** [rad] how far the robot turned over a window of `track` from `start` (graph poses). */
    double windowTurn(const magnetic::SupernodeTrack& track, std::size_t start) const;
    /** The passes' distance that places the robot within distinct_radius: in a turn `turn` the
     * passes' arcs differ in length by the distance times the turn, and the fit, aligning the
     * windows' middles, places the newest reading off along the path by half of that. */
    double nearRadius(double turn) const;
    /** A window of `track` from `start` (read backward if `reversed`) in the displacement
     * model's basis. */
    Eigen::MatrixX3d projectedWindow(const magnetic::SupernodeTrack& track, std::size_t start,
                                     bool reversed) const;
    /** A candidate's differences in that basis, from the query window's projection and its
     * own (kept). */
    Eigen::MatrixX3d projectedResiduals(const Candidate& k, std::size_t start,
                                        const Eigen::MatrixX3d& query) const;
    /** A candidate's differences (query minus turned target). */
    Eigen::MatrixX3d residuals(const Candidate& k, std::size_t first) const;
    /** Same line: every plausible candidate's weight against the null (logWeight). */
    void weighSameLine(const Candidate& best, std::vector<Candidate>& all, std::size_t first,
                       const magnetic::WindowNullModel& null) const;
    /** The posterior of the best candidate's place (candidates within distinct_radius of it,
     * passed within reach) against every other place, passes further apart, and the null. */
    double placePosterior(const Candidate& best, const std::vector<Candidate>& all) const;
    /** An accepted window's closure, measured (MagneticWindowClosures.cpp). */
    struct Closure {
        TNodeID target{0}, query{0};
        mrpt::poses::CPosePDFGaussian z;
        Eigen::Matrix2d positionCov{Eigen::Matrix2d::Identity()};  ///< in the target's frame
        double score{0};
        magnetic::WindowDirection direction{magnetic::WindowDirection::Forward};
        double sQuery{0}, sTarget{0};  ///< [m] travel of the query's newest reading and its match
        int targetSegment{0};
        std::optional<std::size_t> truthRecord;  ///< in truth_queries_
    };
    /** The edge from the target's path to the query node (nullopt: not measurable). */
    std::optional<Closure> measureClosure(const Candidate& best, const std::vector<Candidate>& all,
                                          std::size_t first) const;
    /** `later` continues `earlier`'s match (same direction and path, consistent travel). */
    bool agree(const Closure& earlier, const Closure& later) const;
    /** Commits `c` now, or when confirmed (Params::confirm); true when it made an edge. */
    bool confirm(const Closure& c);
    bool commit(const Closure& c);
    Eigen::Vector2d positionAtSample(const magnetic::SupernodeTrack& track, std::size_t i) const;
    /** The graph's heading at a sample (interpolated in its node's interval). */
    double yawAtSample(const magnetic::SupernodeTrack& track, std::size_t i) const;
    /** Where travel `s` lies in node k's interval (0 at node k - 1, 1 at k); none for a node
     * with no interval (a segment's first). */
    std::optional<double> intervalFraction(TNodeID k, double s) const;
    /** Readings to keep: the queried sensor's and its mirror's (MagneticWindowSensors.cpp). */
    bool takeReading(const MagneticSample& reading);
    const magnetic::SupernodeTrack& queried() const;
    /** The track backward windows are compared with: the mirror's, else the queried one. */
    const magnetic::SupernodeTrack& mirrored() const;

    Params params_;
    std::optional<magnetic::PassNoiseEstimate> noise_;  // learn_noise
    double prior_sigma_{1.0};                           // window_sigma as configured
    double last_learnt_{-1e18};                         // [m] travel of the last window learnt from
    std::size_t n_{0};  // samples per window (rebuild)
    // what the displacement model keeps for every window of n_ samples (rebuild)
    std::shared_ptr<const magnetic::WindowDisplacementModel::Basis> basis_;
    double correlated_samples_{
        0};  // sum of the field kernel's correlations over a window (rebuild)
    struct Sensor {
        std::unique_ptr<magnetic::SupernodeTrack> track;
        Eigen::Vector3d position;       ///< on the robot [m]
        std::vector<char> redundant{};  ///< per sample of a loaded map: not a target (thinMap)
        /** Per sample of a loaded map: the first target from it on (the map's size: none), so
         * a query's scan costs the map's targets, not every reading it holds. */
        std::vector<std::size_t> nextTarget{};
    };
    /** A loaded map's readings thinned (map_thinning_radius), once all its nodes are in
     * (MagneticWindowMapThinning.cpp). */
    void thinMap();
    void thinTrack(Sensor& sensor);
    /** Every target window of a loaded map projected into the displacement model's basis,
     * once its nodes are all in: a run's first queries, before it knows where it is, compare
     * with every one (MagneticWindowMapThinning.cpp). */
    void projectMapTargets();
    std::uint64_t projectionKey(const magnetic::SupernodeTrack& track, std::size_t start,
                                bool backward) const;
    std::map<std::string, Sensor> sensors_;           // the queried one and its mirror
    std::string mirror_;                              // the mirror's label ("": none)
    MagneticPath path_;                               // travel, segment, pose uncertainty per node
    std::vector<const Graph::global_pose_t*> poses_;  // per node, in the graph
    TNodeID seen_{0};
    double last_query_{-1e18}, last_closure_{-1e18};  // [m] travel
    Stats stats_;
    std::deque<Closure> pending_;       // accepted, waiting for confirmation
    std::optional<Closure> confirmed_;  // the last closure of a confirmed match
    std::vector<TruthQuery> truth_queries_;
    // Stored windows in the displacement model's basis, by (start, track, direction); cleared
    // whole when full (20 000 windows of 2 m: about 19 MB).
    static constexpr std::size_t kProjectionCache = 20000;
    mutable std::unordered_map<std::uint64_t, Eigen::MatrixX3d> projected_targets_;
    // A loaded map's target windows in that basis, by the same key: never cleared.
    std::unordered_map<std::uint64_t, Eigen::MatrixX3d> projected_map_;
};

}  // namespace lodestone::graphslam
