#pragma once

#include <lodestone/graphslam/SlamComponent.h>
#include <mrpt/graphslam/interfaces/CNodeRegistrationDecider.h>

#include <functional>
#include <optional>

namespace lodestone::graphslam {

/** Base of Lodestone's node registration deciders: MRPT's CNodeRegistrationDecider (so it runs
 * inside CGraphSlamEngine too) plus what our engine asks of it. Contract: at most one node per
 * updateState(); node IDs 0, 1, 2, ... in order, each with a NodeRecord in the store. */
class NodeDecider : public mrpt::graphslam::deciders::CNodeRegistrationDecider<Graph>,
                    public SlamComponent {
  public:
    /** MRPT's way: the INI file by name. */
    void loadParams(const std::string& source_fname) override;
    /** The data ended: register what is still pending. Returns true if a node was added. */
    virtual bool finish() = 0;
    /** A loaded map holds nodes 0 .. lastMapNode: the run's first node is lastMapNode + 1, in
     * segment `segment`, tied to the map as across a kidnap (the robot is somewhere in it).
     * Called before any observation. The default refuses (std::logic_error). */
    virtual void continueAfterMap(TNodeID lastMapNode, int segment);
    /** Work on an observation that depends on it alone (an RGB-D frame's features and depth
     * cloud), for a reader to do ahead on its own threads, at most `inFlight` observations
     * before updateState() takes them, so that the frame loop need not. Thread-safe; what it
     * computes is what updateState() computes without it. Empty (the default): nothing. */
    virtual std::function<void(const mrpt::obs::CObservation::Ptr&)> preparer(std::size_t inFlight);
    /** Whether keyframes' records carry their depth cloud (NodeRecord::depth): the engine
     * asks it for an edge decider that aligns keyframes' depth. The default ignores it (a
     * decider without depth frames). */
    virtual void keepKeyframeDepth(bool /*keep*/) {}
    /** What the decider's tracking is doing now, in a word or two for a live view
     * ("tracking", "bridging a gap", "lost", ...); empty where it does not say. */
    virtual std::string trackingState() const { return {}; }
    /** The ID registered by the last updateState() / finish() call, if it added one. */
    std::optional<TNodeID> justRegistered() const { return just_registered_; }

  protected:
    std::optional<TNodeID> just_registered_;
};

}  // namespace lodestone::graphslam
