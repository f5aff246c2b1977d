// ProximityERD on a synthetic feature world: a camera that lingers - swaying and turning in
// front of one wall for a minute, never 4 m from where it started - with odometry whose heading
// drifts. Keyframes seconds apart see the same features; each must be linked to the earlier
// ones with the true relative pose, and the links must take the drift out.
#include "../vision/SyntheticFeatures.h"
#include "ConfigErrorOf.h"
#include "ScriptedDeciders.h"

#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/SlamEngine.h>
#include <lodestone/graphslam/Se3Pose.h>
#include <lodestone/graphslam/erd/CompositeERD.h>
#include <lodestone/graphslam/erd/visual/ProximityERD.h>
#include <lodestone/graphslam/gso/CeresGSO.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationComment.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

using namespace lodestone;

namespace {

double yawOf(const Eigen::Isometry3d& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }

/** The lingering camera's true robot poses: 0.5 m of sway across, 0.3 m to and fro, +-25 deg
 * of turn, a node every 0.4 s for a minute (the robot frame's x towards the wall at x = 3). */
std::vector<Eigen::Isometry3d> lingeringPath() {
    std::vector<Eigen::Isometry3d> truth;
    for (int i = 0; i < 150; ++i) {
        const double t = 0.4 * i;
        truth.push_back(test::planarPose(0.15 * std::sin(0.31 * t), 0.25 * std::sin(0.53 * t),
                                         0.44 * std::sin(0.23 * t)));
    }
    return truth;
}

struct LingeringRun {
    std::unique_ptr<graphslam::SlamEngine> engine;
    const graphslam::ProximityERD* erd{nullptr};
    std::vector<Eigen::Isometry3d> truth;
};

/** Every node a keyframe seeing `world` (its features through `featuresOf`, by default the
 * truth's view); odometry the truth's steps with a heading that drifts 0.5 deg a step. */
LingeringRun linger(bool withProximity,
           const std::function<std::shared_ptr<vision::FrameFeatures>(std::size_t)>& featuresOf = {}) {
    static const auto world = test::FeatureWorld::room(3000, 21);
    LingeringRun run;
    run.truth = lingeringPath();
    std::vector<test::ScriptedNRD::Step> steps;
    std::vector<graphslam::NodeRecord> records;
    const double drift = 0.5 * M_PI / 180;
    for (std::size_t i = 0; i < run.truth.size(); ++i) {
        graphslam::NodeRecord r;
        r.timestamp = 0.4 * double(i);
        r.keyframe = true;
        r.features = featuresOf ? featuresOf(i) : test::view(world, run.truth[i], 0.003, 100 + i);
        r.T_robot_camera = test::forwardCamera();
        records.push_back(r);
        if (i == 0) continue;
        Eigen::Isometry3d step = run.truth[i - 1].inverse() * run.truth[i];
        step.linear() = step.linear() * Eigen::AngleAxisd(drift, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        graphslam::Constraint c;
        c.mean = graphslam::poseOf3D(step);
        c.cov_inv.setZero();
        const double sxy = 0.01, sz = 0.001, syaw = 1.0 * M_PI / 180, stilt = 0.1 * M_PI / 180;
        const double var[6] = {sxy * sxy, sxy * sxy, sz * sz, syaw * syaw, stilt * stilt, stilt * stilt};
        for (int k = 0; k < 6; ++k) c.cov_inv(k, k) = 1 / var[k];
        steps.push_back({c, 0});
    }
    auto composite = std::make_unique<graphslam::CompositeERD>();
    if (withProximity) {
        auto erd = std::make_unique<graphslam::ProximityERD>();
        run.erd = erd.get();
        composite->addChild(std::move(erd));
    }
    run.engine = std::make_unique<graphslam::SlamEngine>(
        std::make_unique<test::ScriptedNRD>(steps, records), std::move(composite),
        std::make_unique<graphslam::CeresGSO>());
    const auto tick = mrpt::obs::CObservationComment::Create();
    while (run.engine->process(tick)) {
    }
    run.engine->finish();
    return run;
}

/** The worst heading error of the graph's nodes relative to the first, against the truth. */
double worstYawError(const LingeringRun& run) {
    double worst = 0;
    const auto& g = run.engine->graph();
    for (std::size_t i = 0; i < run.truth.size(); ++i) {
        const double e = std::remainder(g.nodes.at(i).yaw() - yawOf(run.truth[i]), 2 * M_PI);
        worst = std::max(worst, std::abs(e));
    }
    return worst;
}

}  // namespace

TEST(ProximityERD, KeyframesSecondsApartViewingOneWallAreLinkedWithTheTrueRelativePose) {
    const LingeringRun run = linger(true);
    const auto& stats = run.erd->stats();
    EXPECT_GT(stats.accepted, 100u);
    EXPECT_EQ(stats.refusedByGate, 0u);
    std::size_t accepted = 0;
    for (const auto& r : run.erd->records()) {
        if (!r.accepted) continue;
        ++accepted;
        EXPECT_LT(r.from + 1, r.to) << "the keyframe before is VO's, not a proximity link";
        const Eigen::Isometry3d truth = run.truth[r.from].inverse() * run.truth[r.to];
        EXPECT_LT((r.relative.translation() - truth.translation()).norm(), 0.02) << r.from << "->" << r.to;
        EXPECT_LT(Eigen::AngleAxisd(r.relative.linear().transpose() * truth.linear()).angle(),
                  1.0 * M_PI / 180);
    }
    EXPECT_EQ(accepted, stats.accepted);
    for (const auto& lc : run.engine->optimizer().loopClosures()) EXPECT_FALSE(lc.rejected);
}

TEST(ProximityERD, TheLinksTakeOutTheOdometrysHeadingDrift) {
    // 0.5 deg a step over 149 steps: the odometry alone ends 74 deg off.
    const double alone = worstYawError(linger(false));
    const double linked = worstYawError(linger(true));
    EXPECT_GT(alone, 60 * M_PI / 180);
    EXPECT_LT(linked, 3 * M_PI / 180) << "odometry alone: " << alone * 180 / M_PI << " deg";
}

TEST(ProximityERD, ALookAlikeTheOdometryRulesOutIsRefused) {
    // Node 60 sees what the camera saw from half a metre to its left (a repeated texture):
    // its features align with the earlier keyframes, but at a pose the odometry rules out.
    static const auto world = test::FeatureWorld::room(3000, 21);
    const auto truth = lingeringPath();
    const LingeringRun run = linger(true, [&](std::size_t i) {
        Eigen::Isometry3d seenFrom = truth[i];
        if (i == 60) seenFrom = seenFrom * test::planarPose(0, 0.5, 0);
        return test::view(world, seenFrom, 0.003, 100 + i);
    });
    EXPECT_GT(run.erd->stats().refusedByGate, 0u);
    for (const auto& r : run.erd->records()) {
        if (r.to == 60 && r.aligned) {
            EXPECT_FALSE(r.accepted) << "from " << r.from << ": gate " << r.gate2;
        }
    }
}

TEST(ProximityERD, ConfigurationIsStrict) {
    graphslam::ProximityERD erd;
    mrpt::config::CConfigFileMemory ok("[ProximityERD]\nradius = 0.5\nmax_candidates = 2\n");
    erd.configure(ok);
    EXPECT_EQ(erd.params().radius, 0.5);
    EXPECT_EQ(erd.params().maxCandidates, 2u);
    for (const char* bad : {"[ProximityERD]\nradiu = 1\n", "[ProximityERD]\nradius = 0\n",
                            "[ProximityERD]\nmax_candidates = 0\n",
                            "[ProximityERD]\nmax_view_angle_deg = 200\n"}) {
        mrpt::config::CConfigFileMemory ini(bad);
        EXPECT_THROW(erd.configure(ini), config::ConfigError) << bad;
    }
    EXPECT_EQ(erd.params().radius, 0.5);  // a failed read changes nothing
}
