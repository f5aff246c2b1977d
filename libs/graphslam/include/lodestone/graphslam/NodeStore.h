#pragma once

#include <lodestone/graphslam/KeyframeCloud.h>
#include <lodestone/graphslam/PoseGraph.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace lodestone::graphslam {

/** What the engine keeps per node beside its pose, for the edge deciders and the outputs. */
struct NodeRecord {
    double timestamp{0};  ///< [s] of the sensor data the node was placed at
    /** Continuous-odometry segment: 0 from the start, one more after each kidnap. Nodes of a
     * segment that is not anchored yet hang on a weak edge (see SlamEngine). */
    int segment{0};
    bool keyframe{false};  ///< an RGB-D keyframe (a subset of nodes, paper 000 §2.3)
    std::shared_ptr<const KeyframeCloud> cloud;  ///< keyframes only, when maps are kept
};

/** Node records indexed by node ID (the NRD registers IDs 0, 1, 2, ... in order). */
class NodeStore {
  public:
    void add(TNodeID id, NodeRecord record);
    bool has(TNodeID id) const { return id < records_.size(); }
    const NodeRecord& at(TNodeID id) const;
    std::size_t size() const { return records_.size(); }
    const std::vector<NodeRecord>& records() const { return records_; }

  private:
    std::vector<NodeRecord> records_;
};

}  // namespace lodestone::graphslam
