#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/erd/CompositeERD.h>
#include <lodestone/graphslam/DeciderRegistry.h>
#include <lodestone/graphslam/SlamEngine.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>

using namespace lodestone;
using graphslam::DeciderRegistry;

namespace {
std::string errorOf(const std::string& ini) {
    try {
        graphslam::SlamEngine::fromConfig(mrpt::config::CConfigFileMemory(ini));
    } catch (const config::ConfigError& e) {
        return e.what();
    }
    return "no error";
}
}  // namespace

TEST(DeciderRegistry, CreatesLodestoneClassesByName) {
    const auto& reg = DeciderRegistry::instance();
    EXPECT_EQ(reg.makeNodeDecider("FusedOdometryNRD", "test")->getClassName(), "FusedOdometryNRD");
    EXPECT_EQ(reg.makeEdgeDecider("CompositeERD", "test")->getClassName(), "CompositeERD");
    EXPECT_EQ(reg.makeOptimizer("CeresGSO", "test")->getClassName(), "CeresGSO");
}

TEST(DeciderRegistry, UnknownNamesAreClearErrors) {
    const std::string e1 = errorOf("[graphslam]\nnode_decider = FusedOdometryNDR\n");
    EXPECT_NE(e1.find("unknown node registration decider 'FusedOdometryNDR'"), std::string::npos) << e1;
    EXPECT_NE(e1.find("node_decider"), std::string::npos) << e1;
    EXPECT_NE(e1.find("known: FusedOdometryNRD"), std::string::npos) << e1;
    const std::string e2 = errorOf("[graphslam]\noptimizer = CLevMarqGSO\n");
    EXPECT_NE(e2.find("MRPT graph optimizer"), std::string::npos) << e2;
    const std::string e3 = errorOf("[graphslam]\nedge_decider =\n");
    EXPECT_NE(e3.find("no edge registration decider named"), std::string::npos) << e3;
    const std::string e4 = errorOf("[CompositeERD]\nchildren = NoSuchERD\n");
    EXPECT_NE(e4.find("unknown edge registration decider 'NoSuchERD'"), std::string::npos) << e4;
    EXPECT_NE(e4.find("children"), std::string::npos) << e4;
    const std::string e5 = errorOf("[graphslam]\noptimiser = CeresGSO\n");
    EXPECT_NE(e5.find("optimiser"), std::string::npos) << e5;
    EXPECT_NE(errorOf("[CeresGSO]\nmode = 3d\n").find("mode"), std::string::npos);
}

TEST(DeciderRegistry, ShippedConfigsLoadAndMatchTheDefaults) {
    // Each shipped INI and the loop closers it names: its values must be the code's defaults
    // (one source of truth, a test to keep it).
    const std::vector<std::pair<std::string, std::vector<std::string>>> shipped = {
        {"odometry_only.ini", {}},
        {"slam.ini", {"OrbSubmapERD", "MagneticGpERD", "MagneticWindowERD"}},
        {"visual_only.ini", {"OrbSubmapERD"}}};
    const auto& reg = DeciderRegistry::instance();
    for (const auto& [name, children] : shipped) {
        SCOPED_TRACE(name);
        const mrpt::config::CConfigFile ini(std::string(LODESTONE_CONFIG_INI_DIR) + "/slam/" + name);
        const auto engine = graphslam::SlamEngine::fromConfig(ini);
        auto composite = std::make_unique<graphslam::CompositeERD>();
        for (const auto& c : children) composite->addChild(reg.makeEdgeDecider(c, ""));
        const graphslam::SlamEngine defaults(reg.makeNodeDecider("FusedOdometryNRD", ""),
                                             std::move(composite),
                                             reg.makeOptimizer("CeresGSO", ""));
        EXPECT_EQ(engine->describe().str(), defaults.describe().str());
    }
}
