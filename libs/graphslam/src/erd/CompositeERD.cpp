#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/erd/CompositeERD.h>

#include <algorithm>
#include <sstream>

namespace lodestone::graphslam {

CompositeERD::CompositeERD(ChildFactory makeChild) : make_child_(std::move(makeChild)) {
    setClassName("CompositeERD");
}

void CompositeERD::configure(const mrpt::config::CConfigFileBase& ini) {
    config::IniSection s(ini, "CompositeERD", config::sourceName(ini));
    std::istringstream names(s.getString("children", ""));
    std::vector<std::string> wanted;
    for (std::string name; names >> name;) wanted.push_back(name);
    s.finish();
    children_.clear();
    for (const auto& name : wanted) {
        if (name == "CompositeERD") s.fail("children", "a CompositeERD cannot host itself");
        if (!make_child_) s.fail("children", "this CompositeERD was made without a decider factory");
        addChild(make_child_(name, s.where("children")));
        children_.back()->configure(ini);
    }
}

void CompositeERD::addChild(std::unique_ptr<EdgeDecider> child) {
    if (m_graph) child->setGraphPtr(m_graph);
    if (nodes_) child->setNodeStore(nodes_);
    if (truth_) child->setDiagnosticTruth(truth_);
    if (segment_group_) child->setSegmentGroups(segment_group_);
    if (map_nodes_) child->setMapNodes(map_nodes_);
    children_.push_back(std::move(child));
}

bool CompositeERD::updateState(mrpt::obs::CActionCollection::Ptr action,
                               mrpt::obs::CSensoryFrame::Ptr observations,
                               mrpt::obs::CObservation::Ptr observation) {
    bool any = false;
    for (auto& c : children_) any = c->updateState(action, observations, observation) || any;
    return any;
}

void CompositeERD::setGraphPtr(Graph* graph) {
    EdgeDecider::setGraphPtr(graph);
    for (auto& c : children_) c->setGraphPtr(graph);
}

void CompositeERD::setDiagnosticTruth(std::shared_ptr<const std::vector<io::TumPose>> truth) {
    EdgeDecider::setDiagnosticTruth(truth);
    for (auto& c : children_) c->setDiagnosticTruth(truth);
}

void CompositeERD::setMapNodes(TNodeID count) {
    EdgeDecider::setMapNodes(count);
    for (auto& c : children_) c->setMapNodes(count);
}

void CompositeERD::setSegmentGroups(std::function<int(int)> groupOf) {
    for (auto& c : children_) c->setSegmentGroups(groupOf);
    EdgeDecider::setSegmentGroups(std::move(groupOf));
}

void CompositeERD::setNodeStore(NodeStore* nodes) {
    EdgeDecider::setNodeStore(nodes);
    for (auto& c : children_) c->setNodeStore(nodes);
}

std::vector<LoopClosure> CompositeERD::takeNewLoopClosures() {
    std::vector<LoopClosure> all = EdgeDecider::takeNewLoopClosures();
    for (auto& c : children_) {
        for (auto& lc : c->takeNewLoopClosures()) all.push_back(std::move(lc));
    }
    return all;
}

void CompositeERD::closuresKept(const std::vector<LoopClosure>& kept) {
    for (auto& c : children_) c->closuresKept(kept);
}

bool CompositeERD::justInsertedLoopClosure() const {
    for (const auto& c : children_) {
        if (c->justInsertedLoopClosure()) return true;
    }
    return m_just_inserted_lc;
}

void CompositeERD::getEdgesStats(std::map<std::string, int>* edge_type_to_num) const {
    for (const auto& c : children_) c->getEdgesStats(edge_type_to_num);
}

bool CompositeERD::wantsKeyframeDepth() const {
    return std::any_of(children_.begin(), children_.end(),
                       [](const auto& c) { return c->wantsKeyframeDepth(); });
}

std::set<std::string> CompositeERD::requiredObservations() const {
    std::set<std::string> all;
    for (const auto& c : children_) {
        for (const auto& o : c->requiredObservations()) all.insert(o);
    }
    return all;
}

JsonObject CompositeERD::describe() const {
    std::vector<JsonObject> kids;
    for (const auto& c : children_) kids.push_back(c->describe());
    return JsonObject().set("class", getClassName()).set("children", kids);
}

}  // namespace lodestone::graphslam
