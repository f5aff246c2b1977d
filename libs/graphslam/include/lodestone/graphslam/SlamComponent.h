#pragma once

#include <lodestone/graphslam/NodeStore.h>
#include <lodestone/graphslam/ReportJson.h>
#include <lodestone/io/TumTrajectory.h>
#include <mrpt/config/CConfigFileBase.h>

#include <memory>
#include <set>
#include <string>
#include <vector>

namespace lodestone::graphslam {

/** What every Lodestone decider and optimizer adds to MRPT's interfaces: strict configuration
 * from one INI section named after its class, the engine's node records, the observation classes
 * it needs (checked against a rawlog before any work), and its part of report.json. */
class SlamComponent {
  public:
    virtual ~SlamComponent() = default;
    /** Reads the component's section (its class name) strictly: an unknown key is a
     * config::ConfigError naming file, section and key. */
    virtual void configure(const mrpt::config::CConfigFileBase& ini) = 0;
    virtual void setNodeStore(NodeStore* nodes) { nodes_ = nodes; }
    /** The run's true trajectory, when it has one (lodestone-slam --ground-truth): what a
     * decider may report its diagnostics against (a loop closer: which stage lost each true
     * revisit) - never an input to its decisions. */
    virtual void setDiagnosticTruth(std::shared_ptr<const std::vector<io::TumPose>> truth) {
        truth_ = std::move(truth);
    }
    /** MRPT class names of the observations it cannot work without (e.g.
     * "CObservation3DRangeScan"). */
    virtual std::set<std::string> requiredObservations() const { return {}; }
    /** Its parameters and statistics for report.json. */
    virtual JsonObject describe() const = 0;

  protected:
    NodeStore* nodes_{nullptr};
    std::shared_ptr<const std::vector<io::TumPose>> truth_;
};

}  // namespace lodestone::graphslam
