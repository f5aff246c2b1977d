#pragma once

#include <lodestone/graphslam/NodeStore.h>
#include <lodestone/graphslam/PoseGraph.h>
#include <lodestone/graphslam/ReportJson.h>
#include <lodestone/graphslam/erd/magnetic/PathUncertainty.h>
#include <lodestone/magnetic/HyperparameterFit.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace lodestone::graphslam {

/** The path both magnetic loop closers build from the nodes as they come: each node's travel
 * and segment, the pose uncertainty along it, and one magnetometer's readings over each node's
 * interval. */
class MagneticPath {
  public:
    /** What became of the readings. */
    struct Counts {
        std::size_t readings{0}, dropped{0}, otherSensors{0};
    };
    using ReadingSink = std::function<void(double travel, const Eigen::Vector3d& robotField)>;
    /** Readings of any magnetometer: the reading (its label and mounting), its travel and the
     * field in the levelled robot frame. */
    using SensorSink = std::function<void(const MagneticSample& reading, double travel,
                                          const Eigen::Vector3d& robotField)>;
    /** Which readings a caller takes (the others are counted as other sensors'). */
    using SensorFilter = std::function<bool(const MagneticSample& reading)>;

    explicit MagneticPath(const closure::PathUncertainty::Params& p = {}) : uncertainty(p) {}

    /** Node `id` (IDs in order): its odometry edge from id - 1 (none at the first node or
     * across a kidnap: no travel) into `travel` and `uncertainty`; then each reading of the
     * magnetometer `label` (empty: the first one seen, which `label` then names) in the node's
     * record, placed along the step by its time between the previous node's and this one's, in
     * the levelled robot frame (the sensor's mounting applied), to `sink`. NaN, infinite and
     * saturated (a component over `saturation` uT) readings are counted and skipped. */
    void addNode(TNodeID id, const Graph& graph, const NodeStore& nodes, std::string& label,
                 double saturation, const ReadingSink& sink);
    /** The same for the readings `take` accepts, of any magnetometer. */
    void addNode(TNodeID id, const Graph& graph, const NodeStore& nodes, double saturation,
                 const SensorFilter& take, const SensorSink& sink);

    /** A loop closure placed node `query` with `positionCov` in the frame of a node facing
     * `targetYaw` and `yawVariance`: the uncertainty pinned there, in the map frame. */
    void pinClosure(TNodeID query, double targetYaw, const Eigen::Matrix2d& positionCov,
                    double yawVariance);
    /** Every loop closure the optimizer kept (any closer's: `EdgeDecider::closuresKept`)
     * pins its newer node as its own closures do: a closer's gate knows what the graph knows.
     * Nodes this path has not taken in yet are left alone. */
    void pinKept(const std::vector<LoopClosure>& kept, const Graph& graph);
    /** Where `graph` has a reading taken at `travel` during node `node`'s step: along the step
     * from node - 1 by travel (x, y, yaw; at the node itself across a segment start). */
    Eigen::Vector3d poseAt(const Graph& graph, TNodeID node, double travel) const;
    /** The reading counts into report.json's stats: readings, dropped_readings,
     * other_sensor_readings. */
    JsonObject& describeCounts(JsonObject& stats) const;

    std::vector<double> travel;  ///< per node [m]
    std::vector<int> segment;    ///< per node
    closure::PathUncertainty uncertainty;
    Counts counts;
};

/** Readings along a path (their travel, segment and world-frame field, in order) as stretches
 * for magnetic::fitHyperparameters: a reading every 0.05 m of travel, 200 a stretch within
 * one segment (a last one of at least half that), at most 40 spread over the whole path. */
std::vector<magnetic::FieldStretch> fieldFitStretches(const std::vector<double>& travel,
                                                      const std::vector<int>& segment,
                                                      const std::vector<Eigen::Vector3d>& field);

/** A closure from a node at `from` (map frame x, y, yaw) to a place found at `here` with
 * covariance `cov` (map frame): the relative pose, the covariance turned into the node's frame
 * plus `floor`^2 on each position axis. */
mrpt::poses::CPosePDFGaussian closureFrom(const Eigen::Vector3d& from, const Eigen::Vector3d& here,
                                          const Eigen::Matrix3d& cov, double floor);

/** The covariance of a place on a path whose step is `step` (the step's own frame): variance
 * `along2` along it, `across2` across it (a sequence of the field places a node along the
 * path it matched, loosely across). */
Eigen::Matrix2d alongAcross(const mrpt::poses::CPose3D& step, double along2, double across2);

/** query_ms_mean and query_ms_max of per-query times [ms] into report.json's stats. */
JsonObject& describeQueryTimes(JsonObject& stats, const std::vector<double>& queryMs);

}  // namespace lodestone::graphslam
