#include <lodestone/config/IniSection.h>
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
    for (const char* name : {"odometry_only.ini", "slam.ini"}) {
        SCOPED_TRACE(name);
        const mrpt::config::CConfigFile ini(std::string(LODESTONE_CONFIG_INI_DIR) + "/" + name);
        const auto engine = graphslam::SlamEngine::fromConfig(ini);
        // The shipped values are the code's defaults (one source of truth, a test to keep it).
        const auto shipped = engine->describe().str();
        const auto defaults =
            graphslam::SlamEngine(DeciderRegistry::instance().makeNodeDecider("FusedOdometryNRD", ""),
                                  DeciderRegistry::instance().makeEdgeDecider("CompositeERD", ""),
                                  DeciderRegistry::instance().makeOptimizer("CeresGSO", ""))
                .describe()
                .str();
        EXPECT_EQ(shipped, defaults);
    }
}
