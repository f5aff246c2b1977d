#pragma once

#include <lodestone/graphslam/EdgeDecider.h>
#include <lodestone/vision/DescriptorMatcher.h>
#include <lodestone/vision/RigidRansac.h>
#include <lodestone/vision/depth/PointToPlaneIcp.h>

#include <map>
#include <memory>
#include <vector>

namespace lodestone::graphslam {

/** Local loop closure between keyframes that see the same place (proximity detection, as
 * RTAB-Map calls it): each new keyframe is aligned with the earlier keyframes of its segment
 * whose views overlap its own by the graph's current estimate - cameras within `radius` of
 * each other, looking within `max_view_angle_deg` of the same way - and that lie at most
 * `max_travel` of travel back (further back is OrbSubmapERD's domain, its `min_travel_gap`);
 * not the keyframe before it (VO's reference: its step already ties them). At most
 * `max_candidates` a keyframe, the furthest back first (they hold the most drift). Each pair's
 * features are matched and aligned as visual odometry's are (vision::alignKeyframePair), then
 * with `depth` solved again with the two keyframes' depth clouds as VO's joined step
 * (vision::joinKeyframeDepth; the node decider keeps them in the records), and an alignment
 * becomes a node-to-node loop closure when it agrees with the graph's relative pose within the
 * odometry's uncertainty between the two nodes plus its own (chi-square of the position and
 * the heading, `gate_chi2`): a keyframe seconds after another cannot be far from where the
 * odometry put it, so a look-alike is refused here before the optimizer's own test. INI
 * section [ProximityERD]. */
class ProximityERD : public EdgeDecider {
  public:
    struct Params {
        double radius{1.0};             ///< [m] between the two cameras, by the graph
        double maxViewAngleDeg{45.0};   ///< [deg] between their optical axes, by the graph
        double maxTravel{4.0};          ///< [m] of travel back
        std::size_t maxCandidates{3};   ///< aligned per keyframe
        vision::DescriptorMatcher::Params matcher;
        vision::RigidRansac::Params ransac;
        /** Each alignment of features solved again with the keyframes' depth; a pair whose depth
         * does not align (too little overlap) is not linked - its features alone place it to
         * centimetres, coarser than the odometry it would correct - nor one whose depth and
         * features disagree beyond their covariances (one of them is wrong). false: features
         * alone. */
        bool depth{true};
        /** A link is made only where it says more than the odometry's chain between its two
         * nodes already does - its position or its heading variance (floored) below the
         * chain's. Where the odometry is better over that stretch (wheels, VO and depth over a
         * metre: a millimetre), a link can only add its own error. false: every link. */
        bool onlyInformative{false};
        vision::PointToPlaneIcp::Params icp;
        double gateChi2{14.16};         ///< (x, y, yaw) 3 dof, 99.73 %
        double minSigmaXY{0.01};        ///< [m] floor on a closure's claimed precision
        double minSigmaYaw{0.3 * M_PI / 180};  ///< [rad]
        Params();
    };
    /** Every alignment tried, for reports and benchmarks. */
    struct Record {
        TNodeID from{0}, to{0};
        std::size_t matches{0}, inliers{0};
        bool aligned{false}, depthJoined{false}, depthDisagreed{false}, accepted{false};
        double gate2{NAN};  ///< the alignment against the graph's relative pose (aligned ones)
        Eigen::Isometry3d relative{Eigen::Isometry3d::Identity()};  ///< `to` in `from`'s frame
    };
    struct Stats {
        /** (depthFailed: aligned by the features, not linked for the depth - it did not align
         * or disagreed) */
        std::size_t keyframes{0}, candidates{0}, aligned{0}, depthFailed{0}, uninformative{0},
            refusedByGate{0}, accepted{0};
        /** Alignments the depth was solved with, and of them those whose depth and features
         * disagreed beyond their covariances (the covariance then widened to cover both). */
        std::size_t depthJoined{0}, depthDisagreed{0};
        double alignMs{0};  ///< [ms] aligning every pair tried: features, then depth
    };

    ProximityERD();
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    const Params& params() const { return params_; }
    bool updateState(mrpt::obs::CActionCollection::Ptr action,
                     mrpt::obs::CSensoryFrame::Ptr observations,
                     mrpt::obs::CObservation::Ptr observation) override;
    std::set<std::string> requiredObservations() const override {
        return {"CObservation3DRangeScan"};
    }
    JsonObject describe() const override;
    bool wantsKeyframeDepth() const override { return params_.depth; }
    const std::vector<Record>& records() const { return records_; }
    const Stats& stats() const { return stats_; }

  private:
    void onNode(TNodeID id);
    /** Earlier keyframes whose views overlap `id`'s, furthest back first, at most
     * max_candidates. */
    std::vector<TNodeID> candidates(TNodeID id) const;
    void tryPair(TNodeID from, TNodeID to);
    Eigen::Isometry3d poseOf(TNodeID id) const;

    Params params_;
    vision::DescriptorMatcher matcher_;
    vision::RigidRansac ransac_;
    /** The depth clouds of the keyframes still within max_travel (taken from the node store,
     * which then forgets them). */
    std::map<TNodeID, std::shared_ptr<const vision::DepthCloud>> depth_;
    std::vector<double> travel_;  // per node [m], from the odometry edges
    /** Per node: the odometry's variance since the start, summed along the chain - (x, y) per
     * axis [m^2] and yaw [rad^2]; the difference of two nodes' is the chain's between them. */
    std::vector<double> chain_xy_, chain_yaw_;
    std::vector<TNodeID> keyframes_;
    TNodeID seen_{0};
    std::vector<Record> records_;
    Stats stats_;
};

}  // namespace lodestone::graphslam
