#pragma once

#include <lodestone/graphslam/NodeStore.h>
#include <lodestone/graphslam/ReportJson.h>
#include <lodestone/graphslam/erd/magnetic/MagneticPath.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/magnetic/SupernodeTrack.h>

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace lodestone::graphslam {

/** What a magnetic loop closer's recall funnel keeps per query that truly revisits a place:
 * how far the true place got through its tests (`stage`, an index into the closer's stage
 * names), which way it was walked, its distance in the position gate, its fit. */
struct FunnelRecord {
    TNodeID queryNode{0};
    int stage{0};
    bool backward{false};
    double gate2{NAN};
    double fit{NAN};
};

/** The run's true positions of the magnetic closers' readings (diagnostics only). A loaded
 * map's nodes (below `firstNode`) were recorded by another run: this run's truth says nothing
 * of them. */
class TruthPositions {
  public:
    TruthPositions(const std::vector<io::TumPose>& truth, const NodeStore& nodes,
                   const MagneticPath& path, TNodeID firstNode)
        : truth_(truth), nodes_(nodes), path_(path), first_node_(firstNode) {}
    /** The truth nearest node `id`'s time (within 0.1 s), if any. */
    const io::TumPose* atNode(TNodeID id) const;
    /** Where the track sample truly was: between its node and the previous one, by travel. */
    std::optional<Eigen::Vector2d> atSample(const magnetic::TrackSample& sample) const;
    /** The earlier sample of `samples` (up to `travelBefore`) truly nearest `here`, within
     * `radius`. */
    std::optional<std::size_t> nearestSample(const std::vector<magnetic::TrackSample>& samples,
                                             double travelBefore, const Eigen::Vector2d& here,
                                             double radius) const;

  private:
    /** atSample with the truth at its node (`b`) and the node before (`a`) looked up. */
    std::optional<Eigen::Vector2d> atSample(const magnetic::TrackSample& sample,
                                            const io::TumPose* b, const io::TumPose* a) const;
    const std::vector<io::TumPose>& truth_;
    const NodeStore& nodes_;
    const MagneticPath& path_;
    TNodeID first_node_;
};

/** report.json's truth_funnel: counts by stage (named), the share of records at stages from
 * `firstGated` on whose truth lay inside the gate `gateChi2`, and every record. */
JsonObject describeFunnel(const std::vector<FunnelRecord>& records,
                          const std::vector<std::string>& stageNames, int firstGated,
                          double gateChi2);

}  // namespace lodestone::graphslam
