#pragma once

#include <lodestone/graphslam/AttitudePrior.h>
#include <lodestone/graphslam/nrd/KeyframeCloud.h>
#include <lodestone/graphslam/PoseGraph.h>
#include <lodestone/vision/OrbFeatures.h>
#include <lodestone/vision/depth/DepthCloud.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lodestone::graphslam {

/** One magnetometer reading as the nodes keep it (CObservationMagnetometer, flattened). */
struct MagneticSample {
    double timestamp{0};            ///< [s]
    std::string sensorLabel;
    mrpt::math::TVector3D field;    ///< in the sensor frame [uT]
    mrpt::poses::CPose3D sensorPose;  ///< sensor on the robot
};

/** What the engine keeps per node beside its pose, for the edge deciders and the outputs. */
struct NodeRecord {
    double timestamp{0};  ///< [s] of the sensor data the node was placed at
    /** Continuous-odometry segment: 0 from the start, one more after each kidnap. Nodes of a
     * segment that is not anchored yet hang on a weak edge (see SlamEngine). */
    int segment{0};
    /** The first node of a segment after a kidnap: when the robot was lifted and put down
     * [s], as the node decider saw it (NaN when it does not know). */
    double liftTime{NAN}, putDownTime{NAN};
    bool keyframe{false};  ///< an RGB-D keyframe (a subset of nodes, paper 000 §2.3)
    std::shared_ptr<const KeyframeCloud> cloud;  ///< keyframes only, when maps are kept
    /** Keyframes: the ORB features of the node's frame (optical frame) and where that frame
     * sits on the robot: what the visual loop closer matches. */
    std::shared_ptr<const vision::FrameFeatures> features;
    Eigen::Isometry3d T_robot_camera{Eigen::Isometry3d::Identity()};
    /** Keyframes, where an edge decider asked for it (NodeDecider::keepKeyframeDepth): the
     * frame's depth sampled as VO's depth alignment samples it (optical frame), for aligning
     * keyframes' depth; whoever takes it may release it from the store (releaseDepth). */
    std::shared_ptr<const vision::DepthCloud> depth;
    /** Magnetometer readings since the previous node, up to this node's time: what the
     * magnetic matcher builds its sequences from (none while the robot was carried). */
    std::vector<MagneticSample> magnetic;
    /** The node's up as an accelerometer measured it, where one is recorded and used. */
    std::optional<AttitudePrior> attitude;
    /** The odometry edge from the node before into this one: how its (x, y, yaw) moves with
     * each wheel's scale error (left, right; DiffDriveOdometry::scaleJacobian). None across a
     * kidnap, or without encoders. */
    std::optional<Eigen::Matrix<double, 3, 2>> wheelScale;
};

/** Node records indexed by node ID (the NRD registers IDs 0, 1, 2, ... in order). */
class NodeStore {
  public:
    void add(TNodeID id, NodeRecord record);
    bool has(TNodeID id) const { return id < records_.size(); }
    const NodeRecord& at(TNodeID id) const;
    /** Drops node `id`'s depth cloud (its one consumer keeps what it still needs). */
    void releaseDepth(TNodeID id);
    std::size_t size() const { return records_.size(); }
    const std::vector<NodeRecord>& records() const { return records_; }

  private:
    std::vector<NodeRecord> records_;
};

}  // namespace lodestone::graphslam
