// MagneticCrossingERD on scripted walks through a 2-D field: a walk that crosses its own earlier
// legs at an angle closes the loop there, right; a pass 1 m beside an earlier one is never
// "the same place"; a bad INI key is named.
#include <gtest/gtest.h>
#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/erd/magnetic/MagneticCrossingERD.h>
#include <mrpt/config/CConfigFileMemory.h>

#include "ScriptedFloorWalk.h"
#include "ScriptedMagneticRun.h"

using namespace lodestone;
using test::FloorField;

namespace {

struct Run {
    std::vector<mrpt::poses::CPose2D> truth;
    test::ScriptedMagneticRun<graphslam::MagneticCrossingERD> run;
};

/** Walks `corners` with MagneticCrossingERD; the odometry's heading drifts `yawPerStep`
 * [rad] every 0.1 m step (each step's claimed noise as test::floorWalkScript's). */
Run walk(const std::vector<Eigen::Vector2d>& corners, const FloorField& field,
         double yawPerStep = 0) {
    auto script = test::floorWalkScript(corners, field);
    for (auto& step : script.steps) {
        auto& mean = step.edge.mean;
        mean.setYawPitchRoll(mean.yaw() + yawPerStep, 0, 0);
        step.edge.cov_inv(3, 3) = 1.0 / (2e-6 + yawPerStep * yawPerStep);
    }
    Run r;
    r.truth = script.truth;
    r.run = test::runMagneticScript<graphslam::MagneticCrossingERD>(
        std::move(script.steps), std::move(script.records), "[MagneticCrossingERD]\n");
    return r;
}

/** Position error of each closure's `to` placed from the truth of `from`. */
std::vector<double> closureErrors(const Run& r) {
    std::vector<double> out;
    for (const auto& p : r.run.engine->proposals()) {
        const auto& m = p.closure.constraint.mean;
        const auto implied = r.truth[p.closure.from] + mrpt::poses::CPose2D(m.x(), m.y(), m.yaw());
        const auto& to = r.truth[p.closure.to];
        out.push_back(std::hypot(implied.x() - to.x(), implied.y() - to.y()));
    }
    return out;
}

}  // namespace

TEST(MagneticCrossingERD, AWalkThatCrossesItsEarlierLegsClosesThereRight) {
    const FloorField field(11);
    // Three lines mowed east and west 1 m apart, then a leg south to north across all three
    // at x = 4 - never along an earlier line. (A single crossing carries about a length scale
    // of the field: in this field of +-6 uT anomalies it is seldom decisive alone.)
    const auto r =
        walk({{0, 0}, {8, 0}, {8, 1}, {0, 1}, {0, 2}, {8, 2}, {4, -1.5}, {4, 3}}, field, 0.0003);
    const auto errors = closureErrors(r);
    EXPECT_GE(errors.size(), 1u);
    for (const double e : errors) EXPECT_LT(e, 0.3);
    EXPECT_GT(r.run.erd->stats().queries, 20u);
    EXPECT_EQ(r.run.erd->stats().closures, errors.size());
}

TEST(MagneticCrossingERD, APassOneMetreBesideAnEarlierOneIsNotTheSamePlace) {
    const FloorField field(12);
    const auto r = walk({{0, 0}, {20, 0}, {20, 5}, {-3, 5}, {-3, 1}, {20, 1}}, field);
    for (const double e : closureErrors(r)) EXPECT_LT(e, 0.3);
    EXPECT_GT(r.run.erd->stats().queries, 50u);
}

TEST(MagneticCrossingERD, ABadIniNamesTheKey) {
    for (const auto& [body, key] : std::vector<std::pair<std::string, std::string>>{
             {"stretch_lenght = 3\n", "stretch_lenght"},
             {"stretch_length = 0\n", "stretch_length"},
             {"min_log_evidence = nan\n", "min_log_evidence"},
             {"max_yaw_deg = 200\n", "max_yaw_deg"},
             {"grid_cell = 0\n", "grid_cell"}}) {
        graphslam::MagneticCrossingERD erd;
        std::string e = "no error";
        try {
            erd.configure(mrpt::config::CConfigFileMemory("[MagneticCrossingERD]\n" + body));
        } catch (const config::ConfigError& err) {
            e = err.what();
        }
        EXPECT_NE(e.find(key), std::string::npos) << body << " -> " << e;
        EXPECT_NE(e.find("MagneticCrossingERD"), std::string::npos) << e;
    }
}
