// The small shared parts of the NodeDecider, EdgeDecider and GraphOptimizer bases.
#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/EdgeDecider.h>
#include <lodestone/graphslam/GraphOptimizer.h>
#include <lodestone/graphslam/NodeDecider.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/system/filesystem.h>

#include <stdexcept>

namespace lodestone::graphslam {

namespace {
void configureFromFile(SlamComponent& component, const std::string& fname) {
    if (!mrpt::system::fileExists(fname)) {
        throw config::ConfigError("cannot open configuration file '" + fname + "'");
    }
    component.configure(mrpt::config::CConfigFile(fname));
}
}  // namespace

void NodeDecider::loadParams(const std::string& source_fname) { configureFromFile(*this, source_fname); }
void EdgeDecider::loadParams(const std::string& source_fname) { configureFromFile(*this, source_fname); }
void GraphOptimizer::loadParams(const std::string& source_fname) {
    configureFromFile(*this, source_fname);
}

void GraphOptimizer::holdFixed(TNodeID) {
    throw std::logic_error(getClassName() + " cannot hold a map's nodes fixed");
}

void NodeDecider::continueAfterMap(TNodeID, int) {
    throw std::logic_error(getClassName() + " cannot start in a saved map");
}

std::function<void(const mrpt::obs::CObservation::Ptr&)> NodeDecider::preparer(std::size_t) {
    return {};
}

void EdgeDecider::registerNewEdge(const TNodeID& from, const TNodeID& to, const Constraint& c) {
    m_graph->insertEdge(from, to, c);
    LoopClosure lc;
    lc.from = from;
    lc.to = to;
    lc.constraint = c;
    lc.source = getClassName();
    lc.matchId = registered_;
    queued_.push_back(lc);
    ++registered_;
    m_just_inserted_lc = true;
}

void EdgeDecider::registerClosure(TNodeID from, TNodeID to, const Constraint& c,
                                  std::size_t matchId, bool strong, double score,
                                  const std::string& source) {
    registerNewEdge(from, to, c);
    if (!source.empty()) queued_.back().source = source;  // one part of a decider, told apart
    queued_.back().matchId = matchId;
    queued_.back().strong = strong;
    queued_.back().score = score;
}

std::vector<LoopClosure> EdgeDecider::takeNewLoopClosures() {
    std::vector<LoopClosure> out;
    out.swap(queued_);
    m_just_inserted_lc = false;
    return out;
}

void EdgeDecider::getEdgesStats(std::map<std::string, int>* edge_type_to_num) const {
    (*edge_type_to_num)[getClassName()] += static_cast<int>(registered_);
    (*edge_type_to_num)["lc"] += static_cast<int>(registered_);
}

}  // namespace lodestone::graphslam
