#include "RunParts.h"
#include "RunningMesh.h"

#include <lodestone/config/ProgressBar.h>
#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/view/LiveView.h>

#include <mrpt/config/CConfigFile.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace lodestone::slamapp::detail {

namespace {

/** Keeps a magnetometer reading for field_map.png (drawn on the optimized trajectory). */
void keep(const obs::CObservationMagnetometer& m, double t, LoopOutcome& loop) {
    auto& labels = loop.magneticLabels;
    const auto label = static_cast<std::size_t>(
        std::find(labels.begin(), labels.end(), m.sensorLabel) - labels.begin());
    if (label == labels.size()) labels.push_back(m.sensorLabel);
    loop.magnetic.push_back({t, m.sensorPose.translation(), m.magnitude(), label});
}

}  // namespace

LoopOutcome runLoop(RunInputs& in, const SlamRunOptions& options, std::ostream& err,
                    SlamRunResult& result) {
    LoopOutcome loop;
    auto& engine = *in.engine;
    config::ProgressBar progress(err, options.terminal, options.quiet);
    const auto wall0 = std::chrono::steady_clock::now();
    double t0 = NAN, lastMap = 0;
    std::unique_ptr<view::LiveView> live;
    if (options.view) live = view::LiveView::open(err);
    std::unique_ptr<RunningMesh> mesh;
    if (options.mesh) {
        const auto params = dense::DenseParams::read(mrpt::config::CConfigFile(options.config));
        try {
            if (options.live || params.fusion == dense::DenseParams::Fusion::WhileRunning)
                mesh = std::make_unique<RunningMesh>(params, options.outDir, engine.mapNodes());
        } catch (const std::exception& e) {
            // (no frame store: the run goes on without its dense model, and says why)
            loop.runningMesh = graphslam::JsonObject();
            loop.runningMeshWhy = e.what();
        }
    }
    const auto status = [&] {
        view::LiveView::Status s;
        s.dataSeconds = loop.dataSeconds;
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
        s.realTimeFactor = wall > 0 ? loop.dataSeconds / wall : 0;
        s.tracking = engine.nodeDecider().trackingState();
        return s;
    };
    const auto timedNext = [&] {
        const auto before = std::chrono::steady_clock::now();
        auto obs = in.source->next();
        loop.sourceSeconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count();
        return obs;
    };
    try {
        while (auto obs = timedNext()) {
            const double t = mrpt::Clock::toDouble(obs->timestamp);
            if (std::isnan(t0)) t0 = t;
            if (t - t0 > options.maxSeconds) break;
            loop.dataSeconds = std::max(loop.dataSeconds, t - t0);
            if (in.simulator) {
                in.simTruth->write(t, in.simulator->truePose3D(in.simulator->lastTime()));
            }
            if (const auto* m = dynamic_cast<const obs::CObservationMagnetometer*>(obs.get())) {
                keep(*m, t, loop);
            }
            engine.process(obs);
            if (mesh) mesh->observe(obs, engine);
            if (live && live->wantsOffer()) live->offer(engine, status());
            if (options.mapEvery > 0 && !options.mapOut.empty() &&
                t - t0 - lastMap >= options.mapEvery) {
                lastMap = t - t0;
                saveMap(in, options, err, result);
                ++loop.mapsSaved;
            }
            if (options.onProgress) {
                options.onProgress(engine.graph().nodes.size(),
                                   engine.optimizer().loopClosures().size());
            }
            const double fraction =
                in.fractionRead ? in.fractionRead()
                : in.simulator  ? loop.dataSeconds /
                                     std::min(in.simulator->duration(), options.maxSeconds)
                                : 0.0;  // live: no end known
            progress.update(fraction, loop.dataSeconds);
        }
    } catch (const std::exception& e) {
        // A fault in the data: stop here, keep and write what was processed.
        result.error = e.what();
        result.exitCode = 1;
        if (!options.quiet) err << "\n";
        err << "lodestone-slam: error: " << e.what() << "\n"
            << "lodestone-slam: writing what was processed before the fault\n";
    }
    try {
        engine.finish();
    } catch (const std::exception& e) {
        err << "lodestone-slam: error while finishing: " << e.what() << "\n";
        result.exitCode = 1;
        if (result.error.empty()) result.error = e.what();
    }
    if (result.error.empty() && engine.graph().nodes.empty()) {
        // Exit 0 with an empty map would read as success.
        result.error = "the run made no nodes: the node decider got no motion from the " +
                       std::to_string(engine.stats().observations) + " observations (" +
                       std::to_string(engine.stats().frames) +
                       " RGB-D frames) - is this the recording the configured deciders need?";
        result.exitCode = 1;
        err << "lodestone-slam: error: " << result.error << "\n";
    }
    loop.wallSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    // (after the run's own time: like the pass after the run, the model's end is its own cost)
    if (mesh) loop.runningMesh = mesh->finish(engine, loop.mesh, loop.runningMeshWhy);
    progress.finish(loop.dataSeconds);
    if (live) {
        if (options.viewKeepOpen && live->isOpen())
            err << "lodestone-slam: the view stays open until it is closed (q); the outputs follow\n";
        live->finish(engine, status(), options.viewKeepOpen);
    }
    if (in.simTruth) in.simTruth->close();  // the truth of what was run, even if it stopped early
    return loop;
}

}  // namespace lodestone::slamapp::detail
