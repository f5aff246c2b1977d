#pragma once
// A scripted run of one magnetic loop closer alone (MagneticGpERD, MagneticWindowERD): the
// nodes' odometry steps and records (with their magnetometer readings) replayed through the
// engine with CeresGSO, the ERD configured from `ini`.
#include <lodestone/graphslam/gso/CeresGSO.h>
#include <lodestone/graphslam/erd/CompositeERD.h>
#include <lodestone/graphslam/erd/magnetic/MagneticGpERD.h>
#include <lodestone/graphslam/SlamEngine.h>
#include <lodestone/graphslam/erd/magnetic/MagneticWindowERD.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationComment.h>

#include <memory>
#include <string>
#include <vector>

#include "ScriptedDeciders.h"

namespace lodestone::test {

template <typename Erd = graphslam::MagneticGpERD>
struct ScriptedMagneticRun {
    std::unique_ptr<graphslam::SlamEngine> engine;
    const Erd* erd{nullptr};
};

template <typename Erd = graphslam::MagneticGpERD>
ScriptedMagneticRun<Erd> runMagneticScript(
    std::vector<ScriptedNRD::Step> steps, std::vector<graphslam::NodeRecord> records,
    const std::string& ini, std::shared_ptr<const std::vector<io::TumPose>> truth = nullptr) {
    ScriptedMagneticRun<Erd> r;
    auto erd = std::make_unique<Erd>();
    erd->configure(mrpt::config::CConfigFileMemory(ini));
    r.erd = erd.get();
    auto composite = std::make_unique<graphslam::CompositeERD>();
    composite->addChild(std::move(erd));
    r.engine = std::make_unique<graphslam::SlamEngine>(
        std::make_unique<ScriptedNRD>(std::move(steps), std::move(records)), std::move(composite),
        std::make_unique<graphslam::CeresGSO>());
    if (truth) r.engine->setDiagnosticTruth(truth);
    const auto tick = mrpt::obs::CObservationComment::Create();
    while (r.engine->process(tick)) {
    }
    r.engine->finish();
    return r;
}

}  // namespace lodestone::test
