#pragma once

#include <lodestone/graphslam/EdgeDecider.h>
#include <lodestone/graphslam/GraphOptimizer.h>
#include <lodestone/graphslam/NodeDecider.h>
#include <lodestone/graphslam/relocalization/Relocalizer.h>
#include <mrpt/config/CConfigFileBase.h>

#include <memory>
#include <set>
#include <vector>

namespace lodestone::graphslam {

/** Lodestone's small graph-SLAM engine. It drives one node decider, one edge decider and one
 * optimizer observation by observation, as MRPT's CGraphSlamEngine does, but: node poses are
 * only ever changed by the optimizer (no per-node Dijkstra re-estimate), loop closures reach the
 * optimizer as an explicit list, and the optimizer's schedule is its own (CeresGSO: local then
 * full solves).
 *
 * Kidnapped segments: the NRD starts a new segment after a kidnap, tied by a very weak edge.
 * A loop closure joining two segments that are not yet one map is not an edge but a
 * relocation hypothesis (relocalization::Relocalizer); once verified, the later segment (never
 * the map) moves rigidly onto the agreeing closures, which then enter the graph. */
class SlamEngine {
  public:
    SlamEngine(std::unique_ptr<NodeDecider> nrd, std::unique_ptr<EdgeDecider> erd,
               std::unique_ptr<GraphOptimizer> gso,
               relocalization::Relocalizer::Params relocalization = {});

    /** Builds the deciders named in `[graphslam] node_decider / edge_decider / optimizer` and
     * configures each from its own section, the relocalizer from `[relocalization]`. Unknown
     * names, sections or keys throw config::ConfigError. */
    static std::unique_ptr<SlamEngine> fromConfig(const mrpt::config::CConfigFileBase& ini);

    /** Starts the run inside a saved map (before any observation): its graph and node records
     * become nodes 0 .. N-1, one group - the map - for the relocalizer; the loop closers take
     * them in without querying among them; the run's first node starts a segment of its own,
     * tied to the map as across a kidnap, until a verified relocation places it. `frozen`
     * (localize): the map's nodes never move. Throws std::logic_error if a decider cannot. */
    void startInMap(const Graph& graph, std::vector<NodeRecord> records, bool frozen);
    /** The nodes a loaded map holds (0: the run began from nothing). */
    TNodeID mapNodes() const { return map_nodes_; }

    /** One observation through NRD, ERD and optimizer. Returns true if a node was added. */
    bool process(const mrpt::obs::CObservation::Ptr& obs);
    /** End of data: pending odometry becomes a node, the ERD gets a last look, final solve. */
    void finish();

    const Graph& graph() const { return graph_; }
    Graph& graph() { return graph_; }
    const NodeStore& nodes() const { return nodes_; }
    const relocalization::Relocalizer& relocalizer() const { return relocalizer_; }
    NodeDecider& nodeDecider() { return *nrd_; }
    EdgeDecider& edgeDecider() { return *erd_; }
    const EdgeDecider& edgeDecider() const { return *erd_; }
    GraphOptimizer& optimizer() { return *gso_; }
    const GraphOptimizer& optimizer() const { return *gso_; }
    /** The run's true trajectory for the deciders' diagnostics (SlamComponent). */
    void setDiagnosticTruth(const std::shared_ptr<const std::vector<io::TumPose>>& truth);
    /** What a reader may do ahead on its threads for the node decider (NodeDecider::preparer). */
    std::function<void(const mrpt::obs::CObservation::Ptr&)> preparer(std::size_t inFlight) {
        return nrd_->preparer(inFlight);
    }
    /** Union of the deciders' required observation classes. */
    std::set<std::string> requiredObservations() const;
    mrpt::poses::CPose3D currentPose() const;

    struct Stats {
        std::size_t observations{0}, frames{0};
        double nrdSeconds{0}, erdSeconds{0}, gsoSeconds{0};
        std::vector<float> nodeMs;   ///< engine time spent per node (between registrations)
        std::vector<float> frameMs;  ///< engine time per RGB-D observation
        std::size_t relocations{0};  ///< merges of a kidnapped segment into the map
    };
    const Stats& stats() const { return stats_; }

    /** A loop closure as the edge decider proposed it, before the relocalizer or the optimizer
     * judged it: what benchmarks score each matcher on (closures.csv: outputs::ClosureTable). */
    struct Proposal {
        LoopClosure closure;
        bool hypothesis{false};  ///< it joined two groups (a relocation hypothesis)
    };
    const std::vector<Proposal>& proposals() const { return proposals_; }
    /** Engine statistics and every component's describe() for report.json. */
    JsonObject describe() const;

  private:
    void afterNodeDecider(bool newNode);
    /** Moves the merged group rigidly and hands the optimizer the closures that join it. */
    void applyMerge(const relocalization::Relocalizer::Merge& m);

    Graph graph_;
    NodeStore nodes_;
    std::unique_ptr<NodeDecider> nrd_;
    std::unique_ptr<EdgeDecider> erd_;
    std::unique_ptr<GraphOptimizer> gso_;
    relocalization::Relocalizer relocalizer_;
    TNodeID relocalizer_seen_{0};
    Stats stats_;
    std::vector<Proposal> proposals_;
    double since_node_ms_{0};
    TNodeID map_nodes_{0};
};

}  // namespace lodestone::graphslam
