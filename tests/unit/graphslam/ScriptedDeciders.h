#pragma once
// Test doubles: a node decider that replays a list of odometry edges (one node per call) and a
// loop closer that emits prepared closures once both their nodes exist.

#include <lodestone/graphslam/EdgeDecider.h>
#include <lodestone/graphslam/NodeDecider.h>
#include <lodestone/graphslam/SlamEngine.h>
#include <lodestone/graphslam/erd/CompositeERD.h>
#include <lodestone/graphslam/gso/CeresGSO.h>
#include <mrpt/obs/CObservationComment.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <vector>

namespace lodestone::test {

class ScriptedNRD : public graphslam::NodeDecider {
  public:
    struct Step {
        graphslam::Constraint edge;  ///< from the previous node
        int segment{0};
    };
    /** `records`, when given, are the nodes' records (one per node, root first); otherwise
     * each node gets its index as timestamp and its step's segment. */
    explicit ScriptedNRD(std::vector<Step> steps, std::vector<graphslam::NodeRecord> records = {})
        : steps_(std::move(steps)), records_(std::move(records)) {
        setClassName("ScriptedNRD");
    }
    void configure(const mrpt::config::CConfigFileBase&) override {}
    graphslam::JsonObject describe() const override { return graphslam::JsonObject().set("class", "ScriptedNRD"); }
    bool updateState(mrpt::obs::CActionCollection::Ptr, mrpt::obs::CSensoryFrame::Ptr,
                     mrpt::obs::CObservation::Ptr) override {
        just_registered_.reset();
        if (m_prev_registered_nodeID == mrpt::graphs::INVALID_NODEID) {
            m_graph->nodes[0] = mrpt::poses::CPose3D();
            m_prev_registered_nodeID = 0;
            nodes_->add(0, records_.empty() ? graphslam::NodeRecord{} : records_.at(0));
        } else if (next_ < steps_.size()) {
            m_since_prev_node_PDF = steps_[next_].edge;
            registerNewNodeAtEnd();
            graphslam::NodeRecord r;
            r.timestamp = static_cast<double>(next_ + 1);
            r.segment = steps_[next_].segment;
            nodes_->add(m_prev_registered_nodeID, records_.empty() ? r : records_.at(next_ + 1));
            ++next_;
        } else {
            return false;
        }
        just_registered_ = m_prev_registered_nodeID;
        return true;
    }
    bool finish() override { return false; }

  private:
    std::vector<Step> steps_;
    std::vector<graphslam::NodeRecord> records_;
    std::size_t next_{0};
};

class ScriptedLoopCloser : public graphslam::EdgeDecider {
  public:
    explicit ScriptedLoopCloser(std::vector<graphslam::LoopClosure> closures)
        : closures_(std::move(closures)) {
        setClassName("ScriptedLoopCloser");
        // In the order their later node appears, so each step looks at the next one only.
        std::stable_sort(closures_.begin(), closures_.end(), [](const auto& a, const auto& b) {
            return std::max(a.from, a.to) < std::max(b.from, b.to);
        });
    }
    void configure(const mrpt::config::CConfigFileBase&) override {}
    graphslam::JsonObject describe() const override { return graphslam::JsonObject().set("class", "ScriptedLoopCloser"); }
    bool updateState(mrpt::obs::CActionCollection::Ptr, mrpt::obs::CSensoryFrame::Ptr,
                     mrpt::obs::CObservation::Ptr) override {
        bool any = false;
        for (; next_ < closures_.size(); ++next_) {
            const auto& lc = closures_[next_];
            if (!m_graph->nodes.count(lc.from) || !m_graph->nodes.count(lc.to)) break;
            registerNewEdge(lc.from, lc.to, lc.constraint);
            any = true;
        }
        return any;
    }

  private:
    std::vector<graphslam::LoopClosure> closures_;
    std::size_t next_{0};
};

/** A loop closer that closes nothing and records the closures the engine says were kept. */
class KeptClosureRecorder : public graphslam::EdgeDecider {
  public:
    KeptClosureRecorder() { setClassName("KeptClosureRecorder"); }
    void configure(const mrpt::config::CConfigFileBase&) override {}
    graphslam::JsonObject describe() const override {
        return graphslam::JsonObject().set("class", "KeptClosureRecorder");
    }
    bool updateState(mrpt::obs::CActionCollection::Ptr, mrpt::obs::CSensoryFrame::Ptr,
                     mrpt::obs::CObservation::Ptr) override {
        return false;
    }
    void closuresKept(const std::vector<graphslam::LoopClosure>& kept) override {
        for (const auto& lc : kept) this->kept.push_back(lc);
    }
    std::vector<graphslam::LoopClosure> kept;
};

/** An engine run through the scripted nodes (`steps`, `records`) with `closers` as the
 * composite's children and Ceres, to its end; `afterEach` (when given) sees the engine after
 * every step. */
inline std::unique_ptr<graphslam::SlamEngine> runScripted(
    std::vector<ScriptedNRD::Step> steps, std::vector<graphslam::NodeRecord> records,
    std::vector<std::unique_ptr<graphslam::EdgeDecider>> closers,
    const std::function<void(const graphslam::SlamEngine&)>& afterEach = {}) {
    auto composite = std::make_unique<graphslam::CompositeERD>();
    for (auto& c : closers) composite->addChild(std::move(c));
    auto engine = std::make_unique<graphslam::SlamEngine>(
        std::make_unique<ScriptedNRD>(std::move(steps), std::move(records)), std::move(composite),
        std::make_unique<graphslam::CeresGSO>());
    const auto tick = mrpt::obs::CObservationComment::Create();
    while (engine->process(tick)) {
        if (afterEach) afterEach(*engine);
    }
    engine->finish();
    return engine;
}

}  // namespace lodestone::test
