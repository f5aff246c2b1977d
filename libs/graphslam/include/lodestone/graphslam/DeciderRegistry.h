#pragma once

#include <lodestone/graphslam/EdgeDecider.h>
#include <lodestone/graphslam/GraphOptimizer.h>
#include <lodestone/graphslam/NodeDecider.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace lodestone::graphslam {

/** Deciders and optimizers by class name, as graphslam-engine picks them from its INI
 * (MRPT's TUserOptionsChecker keeps the same kind of name -> factory maps). Lodestone's classes
 * are registered on first use; later libraries (the visual and magnetic loop closers) add theirs
 * with the register* functions. An unknown name is a config::ConfigError that lists the known
 * ones. */
class DeciderRegistry {
  public:
    using NodeFactory = std::function<std::unique_ptr<NodeDecider>()>;
    using EdgeFactory = std::function<std::unique_ptr<EdgeDecider>()>;
    using OptimizerFactory = std::function<std::unique_ptr<GraphOptimizer>()>;

    static DeciderRegistry& instance();

    void registerNodeDecider(const std::string& name, NodeFactory f);
    void registerEdgeDecider(const std::string& name, EdgeFactory f);
    void registerOptimizer(const std::string& name, OptimizerFactory f);

    /** `where` says where the name came from ("slam.ini [graphslam] node_decider") for the
     * error message. */
    std::unique_ptr<NodeDecider> makeNodeDecider(const std::string& name,
                                                 const std::string& where) const;
    std::unique_ptr<EdgeDecider> makeEdgeDecider(const std::string& name,
                                                 const std::string& where) const;
    std::unique_ptr<GraphOptimizer> makeOptimizer(const std::string& name,
                                                  const std::string& where) const;

    std::vector<std::string> nodeDeciders() const;
    std::vector<std::string> edgeDeciders() const;
    std::vector<std::string> optimizers() const;

  private:
    DeciderRegistry();
    std::map<std::string, NodeFactory> nodes_;
    std::map<std::string, EdgeFactory> edges_;
    std::map<std::string, OptimizerFactory> optimizers_;
};

}  // namespace lodestone::graphslam
