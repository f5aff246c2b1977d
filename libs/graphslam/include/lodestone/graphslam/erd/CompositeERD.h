#pragma once

#include <lodestone/graphslam/EdgeDecider.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace lodestone::graphslam {

/** The one edge decider the engine talks to: it hosts any number of child loop closers, created
 * by class name from `[CompositeERD] children = NameA NameB`, and forwards every call to each
 * (MRPT's CGraphSlamEngine takes a single ERD, so fusing matchers needs this). Loop closures of
 * all children come out of takeNewLoopClosures() tagged with the child's name. With no children
 * (the default) it adds nothing: an odometry-only run. The children are made by a factory its
 * creator passes (the DeciderRegistry passes its own), so it knows no registry. */
class CompositeERD : public EdgeDecider {
  public:
    /** Makes the child named `name`; `where` names the INI key for an error message. */
    using ChildFactory =
        std::function<std::unique_ptr<EdgeDecider>(const std::string& name, const std::string& where)>;

    /** Without a factory, children come only through addChild (a `children` key is an error). */
    explicit CompositeERD(ChildFactory makeChild = {});
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    /** Adds a child directly (tests, or code that builds its own matcher). */
    void addChild(std::unique_ptr<EdgeDecider> child);
    const std::vector<std::unique_ptr<EdgeDecider>>& children() const { return children_; }

    bool updateState(mrpt::obs::CActionCollection::Ptr action,
                     mrpt::obs::CSensoryFrame::Ptr observations,
                     mrpt::obs::CObservation::Ptr observation) override;
    void setGraphPtr(Graph* graph) override;
    void setNodeStore(NodeStore* nodes) override;
    void setMapNodes(TNodeID count) override;
    void setSegmentGroups(std::function<int(int)> groupOf) override;
    void setDiagnosticTruth(std::shared_ptr<const std::vector<io::TumPose>> truth) override;
    std::vector<LoopClosure> takeNewLoopClosures() override;
    void closuresKept(const std::vector<LoopClosure>& kept) override;
    bool justInsertedLoopClosure() const override;
    void getEdgesStats(std::map<std::string, int>* edge_type_to_num) const override;
    std::set<std::string> requiredObservations() const override;
    bool wantsKeyframeDepth() const override;
    JsonObject describe() const override;

  private:
    ChildFactory make_child_;
    std::vector<std::unique_ptr<EdgeDecider>> children_;
};

}  // namespace lodestone::graphslam
