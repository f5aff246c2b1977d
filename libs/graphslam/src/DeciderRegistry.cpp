#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/gso/CeresGSO.h>
#include <lodestone/graphslam/erd/CompositeERD.h>
#include <lodestone/graphslam/DeciderRegistry.h>
#include <lodestone/graphslam/nrd/FusedOdometryNRD.h>
#include <lodestone/graphslam/nrd/VisualOdometryNRD.h>
#include <lodestone/graphslam/erd/magnetic/MagneticCrossingERD.h>
#include <lodestone/graphslam/erd/magnetic/MagneticFieldMapERD.h>
#include <lodestone/graphslam/erd/magnetic/MagneticGpERD.h>
#include <lodestone/graphslam/erd/visual/OrbSubmapERD.h>
#include <lodestone/graphslam/erd/visual/ProximityERD.h>
#include <lodestone/graphslam/erd/magnetic/MagneticWindowERD.h>

namespace lodestone::graphslam {

namespace {

template <typename Map>
std::vector<std::string> namesOf(const Map& m) {
    std::vector<std::string> out;
    for (const auto& [name, f] : m) out.push_back(name);
    return out;
}

template <typename Map>
auto make(const Map& m, const std::string& name, const std::string& kind, const std::string& where) {
    const auto it = m.find(name);
    if (it != m.end()) {
        auto made = it->second();
        made->setClassName(name);
        return made;
    }
    std::string known;
    for (const auto& n : namesOf(m)) known += (known.empty() ? "" : ", ") + n;
    // MRPT's own deciders drive CGraphSlamEngine's 2D scans; say so rather than "unknown".
    const bool mrpt = name == "CFixedIntervalsNRD" || name == "CICPCriteriaNRD" ||
                      name == "CEmptyNRD" || name == "CICPCriteriaERD" ||
                      name == "CLoopCloserERD" || name == "CEmptyERD" || name == "CLevMarqGSO" ||
                      name == "CEmptyGSO";
    throw config::ConfigError(where + ": " +
                              (name.empty() ? "no " + kind + " named"
                                            : (mrpt ? "'" + name + "' is an MRPT " + kind +
                                                          " for CGraphSlamEngine, not one "
                                                          "lodestone-slam drives"
                                                    : "unknown " + kind + " '" + name + "'")) +
                              " (known: " + known + ")");
}

}  // namespace

DeciderRegistry::DeciderRegistry() {
    registerNodeDecider("FusedOdometryNRD", [] { return std::make_unique<FusedOdometryNRD>(); });
    registerNodeDecider("VisualOdometryNRD", [] { return std::make_unique<VisualOdometryNRD>(); });
    registerEdgeDecider("CompositeERD", [this] {
        return std::make_unique<CompositeERD>(
            [this](const std::string& name, const std::string& where) {
                return makeEdgeDecider(name, where);
            });
    });
    registerEdgeDecider("OrbSubmapERD", [] { return std::make_unique<OrbSubmapERD>(); });
    registerEdgeDecider("ProximityERD", [] { return std::make_unique<ProximityERD>(); });
    registerEdgeDecider("MagneticGpERD", [] { return std::make_unique<MagneticGpERD>(); });
    registerEdgeDecider("MagneticWindowERD", [] { return std::make_unique<MagneticWindowERD>(); });
    registerEdgeDecider("MagneticFieldMapERD", [] { return std::make_unique<MagneticFieldMapERD>(); });
    registerEdgeDecider("MagneticCrossingERD", [] { return std::make_unique<MagneticCrossingERD>(); });
    registerOptimizer("CeresGSO", [] { return std::make_unique<CeresGSO>(); });
}

DeciderRegistry& DeciderRegistry::instance() {
    static DeciderRegistry registry;
    return registry;
}

void DeciderRegistry::registerNodeDecider(const std::string& name, NodeFactory f) {
    nodes_[name] = std::move(f);
}
void DeciderRegistry::registerEdgeDecider(const std::string& name, EdgeFactory f) {
    edges_[name] = std::move(f);
}
void DeciderRegistry::registerOptimizer(const std::string& name, OptimizerFactory f) {
    optimizers_[name] = std::move(f);
}

std::unique_ptr<NodeDecider> DeciderRegistry::makeNodeDecider(const std::string& name,
                                                              const std::string& where) const {
    return make(nodes_, name, "node registration decider", where);
}
std::unique_ptr<EdgeDecider> DeciderRegistry::makeEdgeDecider(const std::string& name,
                                                              const std::string& where) const {
    return make(edges_, name, "edge registration decider", where);
}
std::unique_ptr<GraphOptimizer> DeciderRegistry::makeOptimizer(const std::string& name,
                                                               const std::string& where) const {
    return make(optimizers_, name, "graph optimizer", where);
}

std::vector<std::string> DeciderRegistry::nodeDeciders() const { return namesOf(nodes_); }
std::vector<std::string> DeciderRegistry::edgeDeciders() const { return namesOf(edges_); }
std::vector<std::string> DeciderRegistry::optimizers() const { return namesOf(optimizers_); }

}  // namespace lodestone::graphslam
