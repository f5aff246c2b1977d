#pragma once

#include <lodestone/graphslam/SlamComponent.h>
#include <mrpt/graphslam/interfaces/CEdgeRegistrationDecider.h>

#include <functional>
#include <map>
#include <vector>

namespace lodestone::graphslam {

/** Base of Lodestone's edge registration deciders (loop closers): MRPT's
 * CEdgeRegistrationDecider, with the loop-closure signal made explicit. A decider calls
 * registerNewEdge(from, to, c) as in MRPT; the edge goes into the graph and is queued for the
 * engine, which hands it to the optimizer. */
class EdgeDecider : public mrpt::graphslam::deciders::CEdgeRegistrationDecider<Graph>,
                    public SlamComponent {
  public:
    void loadParams(const std::string& source_fname) override;
    /** Adds the edge to the graph and queues it as a loop closure from this decider. */
    void registerNewEdge(const TNodeID& from, const TNodeID& to, const Constraint& c) override;
    /** The loop closures registered since the last call (the engine empties the queue after
     * every step). */
    virtual std::vector<LoopClosure> takeNewLoopClosures();
    /** The loop closures of every decider that the optimizer kept this step (the engine calls
     * it after solving): what the graph now knows of where its newest nodes are, whoever
     * found it. A decider that gates by its own path's uncertainty pins it there. */
    virtual void closuresKept(const std::vector<LoopClosure>& /*kept*/) {}
    /** It aligns keyframes' depth: the node decider is to keep each keyframe's depth cloud in
     * its record (NodeRecord::depth). */
    virtual bool wantsKeyframeDepth() const { return false; }
    /** MRPT's statistics: this decider's class name and "lc" (what CGraphSlamEngine counts). */
    void getEdgesStats(std::map<std::string, int>* edge_type_to_num) const override;
    std::size_t loopClosuresRegistered() const { return registered_; }
    /** Nodes with an ID below `count` are a loaded map's (SlamEngine::startInMap): taken in as
     * every node is, never queried from - a map's own closures are in it already. */
    virtual void setMapNodes(TNodeID count) { map_nodes_ = count; }
    /** Which segments share a frame (SlamEngine: the relocalizer's groups - a kidnapped
     * segment, or a run started in a map, joins the map's once relocated): the graph's
     * positions compare across segments of one group, and a loop closer may gate by them. */
    virtual void setSegmentGroups(std::function<int(int)> groupOf) { segment_group_ = std::move(groupOf); }

  protected:
    /** Positions of the two segments compare (the same segment, or joined). */
    bool sameFrame(int segmentA, int segmentB) const {
        return segmentA == segmentB ||
               (segment_group_ && segment_group_(segmentA) == segment_group_(segmentB));
    }
    TNodeID map_nodes_{0};
    std::function<int(int)> segment_group_;
    /** registerNewEdge with what the relocalizer weighs: closures sharing `matchId` come from
     * one match (not independent evidence); `strong` when the match alone is convincing by
     * the decider's own threshold; `score` is the decider's measure of the evidence (higher
     * is stronger, see LoopClosure::score). registerNewEdge gives every closure a match of its
     * own. `source`, if given, replaces the class name as the closure's source (one method of
     * a decider told apart from its others in closures.csv). */
    void registerClosure(TNodeID from, TNodeID to, const Constraint& c, std::size_t matchId,
                         bool strong, double score, const std::string& source = {});

    std::vector<LoopClosure> queued_;
    std::size_t registered_{0};
};

}  // namespace lodestone::graphslam
