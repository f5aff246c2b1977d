#pragma once

#include <lodestone/graphslam/PoseGraph.h>

#include <Eigen/Core>
#include <vector>

namespace lodestone::graphslam::closure {

/** The x, y, yaw block of an edge's covariance (MRPT order x, y, z, yaw, pitch, roll); 1e6 I
 * where the edge holds no information there. */
Eigen::Matrix3d planarCovariance(const Constraint& c);

/** What PathUncertainty adds to the odometry's own claims. */
struct PathUncertaintyParams {
    double headingBias{0.005};  ///< [rad/m] 1 sigma of the systematic heading drift
    double floor{0.5};          ///< [m] added to the position sigma (map error, placement)
};

/** How far the robot may be from where the graph has it, relative to the last place a loop
 * closure pinned: the odometry's covariance propagated node by node along the odometry edges
 * (first order, in the map frame: each step's own covariance turned into the map frame, and
 * the heading's variance swinging the step with its lever arm), plus a systematic heading drift
 * per metre (uncalibrated wheels, a gyro's bias) as a random constant of variance
 * `headingBias`^2 whose effect grows with the travel since the pin. A loop closure resets a
 * node to the closure's covariance; the nodes after it are propagated again. A segment (after
 * a kidnap) starts certain in its own frame: its relation to the map is not this class's
 * business.
 *
 * Loop-closure searches use it as a gate: a stored place can be where the robot is only if
 * their distance, under this covariance plus `floor`^2 for the map's own error, is inside a
 * chi-square gate - instead of a fixed radius. */
class PathUncertainty {
  public:
    using Params = PathUncertaintyParams;
    explicit PathUncertainty(Params p = {}) : params_(p) {}

    /** Node `id` (IDs in order, from 0) with the odometry edge from id-1 that led to it
     * (`edge`: nullptr at the first node or across a kidnap: a new segment starts certain),
     * and the heading of node id-1 in the map [rad]. */
    void addNode(TNodeID id, const Constraint* edge, double previousYaw);
    /** A loop closure pins `id` with `covariance` (map frame x, y, yaw); later nodes follow. */
    void pin(TNodeID id, const Eigen::Matrix3d& covariance);
    /** Map-frame covariance of x, y, yaw at `id` (the drift term included). */
    Eigen::Matrix3d covariance(TNodeID id) const;
    /** Squared Mahalanobis distance of the map-frame offset `d` between `id` and a stored
     * place, under its position covariance plus floor^2 I. */
    double gateDistance2(TNodeID id, const Eigen::Vector2d& d) const;
    /** Squared Mahalanobis distance of the offset `d` of `query` from the earlier node
     * `target` under their relative uncertainty: where `target` lies on the chain since the
     * place `query` is known from (its last pin or segment start), the covariance of the error
     * of their offset - what the odometry between them added, plus the target's heading and
     * drift errors swinging the path between them (exact for the linear model, from prefix
     * sums: O(1)); a place a few metres back on the same unbroken path is not "anywhere the
     * robot may have drifted". Otherwise both uncertainties added. Plus floor^2 I, as
     * gateDistance2. */
    double relativeGateDistance2(TNodeID target, TNodeID query, const Eigen::Vector2d& d) const;
    /** The covariances the two gate distances weigh an offset by (floor^2 I included). */
    Eigen::Matrix2d gateCovariance(TNodeID id) const;
    Eigen::Matrix2d relativeGateCovariance(TNodeID target, TNodeID query) const;
    /** The least squared Mahalanobis distance, under covariance `S`, from `p` to the segment
     * from `a` to `b`: a lower bound of the gate distance of every place on it. */
    static double segmentDistance2(const Eigen::Matrix2d& S, const Eigen::Vector2d& a,
                                   const Eigen::Vector2d& b, const Eigen::Vector2d& p);
    std::size_t size() const { return steps_.size(); }
    const Params& params() const { return params_; }

  private:
    // State x, y, yaw, heading bias [rad/m]; the bias keeps its prior variance.
    using Matrix4 = Eigen::Matrix4d;
    struct Step {
        bool segmentStart{true};
        Eigen::Vector2d delta{Eigen::Vector2d::Zero()};  ///< the step in the map frame
        double length{0};                                ///< [m]
        double previousYaw{0};
        Eigen::Matrix3d stepCovariance{Eigen::Matrix3d::Zero()};  ///< in the frame of id-1
    };
    void propagate(std::size_t from);
    Matrix4 startState() const;

    Params params_;
    std::vector<Step> steps_;
    std::vector<Matrix4> sigma_;
    std::vector<TNodeID> reference_;  // per node: its last pin or segment start
    /** Per node, summed over the steps so far: travel, map-frame position, and the steps'
     * map-frame components weighted by the travel before them (what the drift swings). */
    struct Prefix {
        double s{0};
        Eigen::Vector2d p{Eigen::Vector2d::Zero()}, weighted{Eigen::Vector2d::Zero()};
    };
    std::vector<Prefix> prefix_;
    std::vector<bool> pinned_;
};

}  // namespace lodestone::graphslam::closure
