#pragma once

#include <lodestone/graphslam/EdgeDecider.h>
#include <lodestone/vision/SubmapCatalog.h>
#include <lodestone/vision/SubmapMatcher.h>

#include <memory>
#include <vector>

namespace lodestone::graphslam {

/** Visual loop closure, paper 000 §2.1: keyframes' ORB features accumulate into submaps
 * (eq. 1) that close when the odometry's uncertainty since their first node passes
 * `submap_max_sigma`, or at `submap_max_keyframes` / `submap_max_length` /
 * `submap_max_features`; each new keyframe is matched in two phases (SubmapMatcher) against
 * candidate submaps: those near where the graph says the robot is (within `search_radius` plus
 * `drift_per_metre` of the distance since the last accepted closure) and those that look alike
 * (appearance index). The best match becomes a node-to-node loop closure. Submaps the robot
 * left less than `min_travel_gap` ago are not candidates (their nodes are tied by odometry).
 * INI section [OrbSubmapERD]. */
class OrbSubmapERD : public EdgeDecider {
  public:
    struct Params {
        vision::FeatureSubmap::Params submap;
        vision::SubmapMatcher::Params matcher;
        int submapMaxKeyframes{6};
        double submapMaxLength{2.0};     ///< [m] travelled from the first node
        double submapMaxSigma{0.05};     ///< [m] odometry position std since the first node
        std::size_t submapMaxFeatures{4000};
        double minTravelGap{4.0};        ///< [m]
        double searchRadius{1.5};        ///< [m]
        double driftPerMetre{0.03};
        std::size_t nearCandidates{2};
        std::size_t similarCandidates{3};
        int minVotes{12};
        double minSigmaXY{0.01};   ///< [m] floor on a closure's claimed precision
        double minSigmaYaw{0.3 * M_PI / 180};  ///< [rad]
        /** A match with this many inliers relocates a kidnapped segment on its own (0: never;
         * relocation then needs a second, independent match that agrees). */
        int strongInliers{0};
    };

    /** One accepted closure, for reports and benchmarks. */
    struct Record {
        TNodeID from{0}, to{0};
        std::size_t submap{0};
        bool phase2{false};
        std::size_t inliers{0}, phase2Inliers{0};
        Eigen::Isometry3d relative{Eigen::Isometry3d::Identity()};  ///< `to` in `from`'s frame
    };
    /** Every query (one per keyframe with candidates), for benchmarks. */
    struct Query {
        TNodeID node{0};
        std::size_t candidates{0};
        std::size_t bestMatches{0}, bestInliers{0};  ///< phase 1, over its candidates
        bool accepted{false};
        double retrievalMs{0}, slowestMatchMs{0};
    };
    struct Stats {
        std::size_t keyframes{0}, submaps{0}, queries{0}, candidatesTried{0}, accepted{0},
            phase2Used{0};
        double retrievalMs{0}, matchMs{0}, buildMs{0};
        double phase1Ms{0}, phase2Ms{0};  ///< parts of matchMs
    };

    OrbSubmapERD();
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    const Params& params() const { return params_; }
    bool updateState(mrpt::obs::CActionCollection::Ptr action,
                     mrpt::obs::CSensoryFrame::Ptr observations,
                     mrpt::obs::CObservation::Ptr observation) override;
    std::set<std::string> requiredObservations() const override { return {"CObservation3DRangeScan"}; }
    JsonObject describe() const override;

    const std::vector<Record>& records() const { return records_; }
    const std::vector<Query>& queries() const { return queries_; }
    const Stats& stats() const { return stats_; }
    const vision::SubmapCatalog& catalog() const { return *catalog_; }

  private:
    void onNode(TNodeID id);
    void query(TNodeID id, const NodeRecord& rec);
    void addToOpenSubmap(TNodeID id, const NodeRecord& rec);
    void closeOpenSubmap();
    Eigen::Isometry3d poseOf(TNodeID id) const;
    void refreshCentres();

    Params params_;
    std::unique_ptr<vision::SubmapMatcher> matcher_;
    std::unique_ptr<vision::SubmapCatalog> catalog_;
    std::shared_ptr<vision::FeatureSubmap> open_;
    TNodeID open_first_{0};
    double open_travel_start_{0}, open_variance_{0};
    std::vector<double> travel_;          // per node: distance travelled since the start [m]
    std::vector<double> submap_end_travel_;  // per closed submap: travel at its last node
    std::vector<TNodeID> submap_first_;      // per closed submap: its first node
    double travel_at_last_closure_{0};
    TNodeID seen_{0};
    std::size_t nodes_since_refresh_{0};
    std::vector<Record> records_;
    std::vector<Query> queries_;
    Stats stats_;
};

}  // namespace lodestone::graphslam
