#include <lodestone/config/IniSection.h>
#include <lodestone/eval/FieldMapPlot.h>
#include <lodestone/eval/TrajectoryError.h>
#include <lodestone/eval/TrajectoryPlot.h>
#include <lodestone/graphslam/ClosureLog.h>
#include <lodestone/graphslam/DeciderRegistry.h>
#include <lodestone/graphslam/nrd/FusedOdometryNRD.h>
#include <lodestone/graphslam/MapExport.h>
#include <lodestone/graphslam/SlamEngine.h>
#include <lodestone/io/KidnapEvents.h>
#include <lodestone/io/PrefetchingSource.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/io/RawlogPaths.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/obs/registerAllClasses.h>
#include <lodestone/sim/SimulatorSource.h>
#include <lodestone/slamapp/GraphPlot.h>
#include <lodestone/config/ProgressBar.h>
#include <lodestone/slamapp/SlamRun.h>
#include <mrpt/config/CConfigFile.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <thread>

#include <sched.h>

namespace lodestone::slamapp {

namespace {

namespace fs = std::filesystem;
using graphslam::JsonObject;

/** Every file a run writes in its output directory. */
constexpr const char* kOutputs[] = {"trajectory.tum", "graph.graph",  "closures.csv",
                                    "map.ply",        "graph.png",    "trajectory.png",
                                    "report.json",    "ground_truth.tum", "events.txt",
                                    "map_at_first_kidnap.tum", "field_map.png",
                                    "nodes.csv"};

// The field map's cell [m]: the magnetic matcher's resample step is 0.05 m and a map read by
// eye needs a few readings per cell at walking speed and 100 Hz.
constexpr double kFieldMapCell = 0.1;

/** A magnetometer reading kept for field_map.png, drawn once the trajectory is optimized. */
struct KeptReading {
    double time;
    mrpt::math::TPoint3D sensorOffset;
    double magnitude;
    std::size_t label;  // index into the run's label list
};

/** Input problems found before any work: the message is the whole story. */
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// How far into a rawlog to look for the observation classes the deciders need: every sensor
// of a recording shows up within its first seconds.
constexpr std::size_t kPrescanObservations = 3000;

std::set<std::string> allowedSections() {
    std::set<std::string> s{"graphslam",       "relocalization",  "kidnap_detection",
                            "wheel_odometry",  "visual_odometry", "odometry_fusion"};
    const auto& reg = graphslam::DeciderRegistry::instance();
    for (const auto& names : {reg.nodeDeciders(), reg.edgeDeciders(), reg.optimizers()}) {
        s.insert(names.begin(), names.end());
    }
    return s;
}

std::string join(const std::set<std::string>& items) {
    std::string out;
    for (const auto& i : items) out += (out.empty() ? "" : ", ") + i;
    return out;
}

void checkRawlogHasObservations(const std::string& path, const std::set<std::string>& required) {
    io::RawlogSource source(path);
    std::set<std::string> missing = required, classes;
    std::size_t seen = 0;
    while (!missing.empty() && seen < kPrescanObservations) {
        const auto obs = source.next();
        if (!obs) break;
        ++seen;
        // MRPT names classes with their namespace; deciders ask by the bare class name.
        const std::string name = obs->GetRuntimeClass()->className;
        const auto colons = name.rfind("::");
        const std::string bare = colons == std::string::npos ? name : name.substr(colons + 2);
        missing.erase(bare);
        classes.insert(bare);
    }
    if (!missing.empty()) {
        // RGB-D frames and no wheels: a camera-only recording, which has its own INI.
        const bool cameraOnly = missing.count("CObservationOdometry") &&
                                classes.count("CObservation3DRangeScan");
        throw InputError(path + ": no " + join(missing) + " among its first " +
                         std::to_string(seen) + " observations; the configured deciders need " +
                         join(required) +
                         (cameraOnly ? ". A camera-only recording (RGB-D, no wheel odometry) runs "
                                       "with config_ini/rgbd_only.ini"
                                     : ""));
    }
}

/** The cores this process may run on (taskset / cgroup affinity), not the machine's. */
std::size_t usableCores() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof(set), &set) == 0) {
        return std::max(1, CPU_COUNT(&set));
    }
    return std::max(1u, std::thread::hardware_concurrency());
}

struct Percentiles {
    double p50{0}, p99{0}, max{0}, mean{0};
};
Percentiles percentiles(std::vector<float> v) {
    Percentiles p;
    if (v.empty()) return p;
    std::sort(v.begin(), v.end());
    const auto at = [&](double q) {
        return static_cast<double>(v[std::min(v.size() - 1, static_cast<std::size_t>(q * v.size()))]);
    };
    p.p50 = at(0.5);
    p.p99 = at(0.99);
    p.max = v.back();
    double sum = 0;
    for (float x : v) sum += x;
    p.mean = sum / v.size();
    return p;
}

/** Mean engine time per node in each tenth of the run: flat means no growth with the graph. */
std::vector<double> decileMeans(const std::vector<float>& v) {
    std::vector<double> out;
    if (v.size() < 10) return out;
    for (int d = 0; d < 10; ++d) {
        const std::size_t a = v.size() * d / 10, b = v.size() * (d + 1) / 10;
        double sum = 0;
        for (std::size_t i = a; i < b; ++i) sum += v[i];
        out.push_back(sum / std::max<std::size_t>(1, b - a));
    }
    return out;
}

JsonObject timingJson(const graphslam::SlamEngine::Stats& s, double wall, double data,
                      double sourceSeconds, std::size_t observations) {
    const auto frames = percentiles(s.frameMs), nodes = percentiles(s.nodeMs);
    return JsonObject()
        .set("wall_s", wall)
        // Waiting for the next observation: reading and decoding it in the frame loop, or with
        // --decode-ahead what the worker had not done yet.
        .set("source_s", sourceSeconds)
        .set("source_ms_per_observation",
             observations > 0 ? 1e3 * sourceSeconds / static_cast<double>(observations) : 0.0)
        .set("data_s", data)
        .set("real_time_factor", wall > 0 ? data / wall : 0.0)
        .set("frame_ms", JsonObject()
                             .set("mean", frames.mean)
                             .set("p50", frames.p50)
                             .set("p99", frames.p99)
                             .set("max", frames.max))
        .set("node_ms", JsonObject().set("mean", nodes.mean).set("p99", nodes.p99).set("max", nodes.max))
        .set("node_ms_by_decile", decileMeans(s.nodeMs));
}

// A source the caller keeps too (lodestone-grab feeds it while the run reads it).
class SharedSource : public io::DataSource {
  public:
    explicit SharedSource(std::shared_ptr<io::DataSource> s) : s_(std::move(s)) {}
    mrpt::obs::CObservation::Ptr next() override { return s_->next(); }
    std::string name() const override { return s_->name(); }

  private:
    std::shared_ptr<io::DataSource> s_;
};

std::vector<io::TumPose> nodeTrajectory(const graphslam::SlamEngine& engine) {
    std::vector<io::TumPose> out;
    const auto& nodes = engine.nodes();
    for (graphslam::TNodeID id = 0; id < nodes.size(); ++id) {
        if (engine.graph().nodes.count(id)) {
            out.push_back({nodes.at(id).timestamp, engine.graph().nodes.at(id)});
        }
    }
    return out;
}

}  // namespace

void checkSlamConfig(const std::string& configPath) {
    if (!fs::exists(configPath)) throw InputError("cannot open configuration file '" + configPath + "'");
    const mrpt::config::CConfigFile ini(configPath);
    config::checkSections(ini, allowedSections(), configPath);
    graphslam::SlamEngine::fromConfig(ini);
}

SlamRunResult runSlam(const SlamRunOptions& options, std::ostream& out, std::ostream& err) {
    SlamRunResult result;
    lodestone::registerAllClasses();
    std::unique_ptr<graphslam::SlamEngine> engine;
    std::unique_ptr<io::DataSource> source;
    sim::SimulatorSource* simulator = nullptr;
    std::function<double()> fractionRead;  // of the rawlog, for the progress bar
    const io::PrefetchingSource* prefetcher = nullptr;  // its workers' time, for report.json
    std::size_t decodeThreads = 0;
    std::unique_ptr<io::TumTrajectoryWriter> simTruth;
    const fs::path dir(options.outDir);
    // --- Everything that can be wrong with the inputs, before any work --------------------------
    try {
        if (!fs::exists(options.config)) throw InputError("cannot open configuration file '" + options.config + "'");
        const mrpt::config::CConfigFile ini(options.config);
        config::checkSections(ini, allowedSections(), options.config);
        engine = graphslam::SlamEngine::fromConfig(ini);
        if (options.live) {
            source = std::make_unique<SharedSource>(options.live);
        } else if (!options.scenario.empty()) {
            const auto scenario = sim::Scenario::load(options.scenario);
            auto sim = std::make_unique<sim::SimulatorSource>(scenario, scenario.seed);
            if (auto* nrd = dynamic_cast<graphslam::FusedOdometryNRD*>(&engine->nodeDecider())) {
                // The simulated robot's wheels are the scenario's, whatever the INI says.
                nrd->setWheelGeometry(scenario.motion.wheelBase, scenario.motion.wheelRadius,
                                      scenario.encoders.ticksPerRev);
            }
            simulator = sim.get();
            source = std::move(sim);
        } else {
            if (!fs::exists(options.rawlog)) throw InputError("cannot open rawlog '" + options.rawlog + "'");
            checkRawlogHasObservations(options.rawlog, engine->requiredObservations());
            auto rl = std::make_unique<io::RawlogSource>(options.rawlog);
            if (options.decodeAhead > 0) {
                const io::RawlogSource* inner = rl.get();
                decodeThreads = options.decodeThreads > 0 ? options.decodeThreads : usableCores();
                auto p = std::make_unique<io::PrefetchingSource>(
                    std::move(rl), options.decodeAhead, [inner] { return inner->fractionRead(); },
                    decodeThreads);
                const io::PrefetchingSource* prefetch = p.get();
                prefetcher = prefetch;
                fractionRead = [prefetch] { return prefetch->progress(); };
                source = std::move(p);
            } else {
                const io::RawlogSource* inner = rl.get();
                fractionRead = [inner] { return inner->fractionRead(); };
                source = std::move(rl);
            }
        }
        if (!options.groundTruth.empty()) {
            if (!fs::exists(options.groundTruth)) {
                throw InputError("cannot open ground truth '" + options.groundTruth + "'");
            }
            // Read now, not after the run: a bad line is named before any work. The deciders
            // may report their diagnostics against it.
            engine->setDiagnosticTruth(std::make_shared<const std::vector<io::TumPose>>(
                io::readTumTrajectory(options.groundTruth)));
        }
        std::error_code ec;
        fs::create_directories(dir, ec);
        if (ec || !fs::is_directory(dir)) {
            throw InputError("cannot create output directory '" + options.outDir + "': " + ec.message());
        }
        // A previous run's outputs must not stay beside this one's if this one stops early.
        for (const char* name : kOutputs) {
            fs::remove(dir / name, ec);
            fs::remove(io::partialPath((dir / name).string()), ec);
        }
        if (simulator) {
            simTruth = std::make_unique<io::TumTrajectoryWriter>((dir / "ground_truth.tum").string());
            io::writeKidnapEvents((dir / "events.txt").string(), simulator->scenario().name,
                                  sim::kidnapRecords(*simulator));
        }
    } catch (const std::exception& e) {
        err << "lodestone-slam: error: " << e.what() << "\n";
        result.exitCode = 1;
        result.error = e.what();
        return result;
    }

    // --- The run ---------------------------------------------------------------------------------
    config::ProgressBar progress(err, options.terminal, options.quiet);
    const auto wall0 = std::chrono::steady_clock::now();
    double t0 = NAN, dataSeconds = 0, sourceSeconds = 0;
    const auto timedNext = [&] {
        const auto before = std::chrono::steady_clock::now();
        auto obs = source->next();
        sourceSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count();
        return obs;
    };
    std::vector<KeptReading> magnetic;  // 48 bytes a reading: 35 MB for an hour of two at 100 Hz
    std::vector<std::string> magneticLabels;
    try {
        while (auto obs = timedNext()) {
            const double t = mrpt::Clock::toDouble(obs->timestamp);
            if (std::isnan(t0)) t0 = t;
            if (t - t0 > options.maxSeconds) break;
            dataSeconds = std::max(dataSeconds, t - t0);
            if (simulator) {
                simTruth->write(t, simulator->truePose3D(simulator->lastTime()));
            }
            if (const auto* m = dynamic_cast<const obs::CObservationMagnetometer*>(obs.get())) {
                const auto label = static_cast<std::size_t>(
                    std::find(magneticLabels.begin(), magneticLabels.end(), m->sensorLabel) -
                    magneticLabels.begin());
                if (label == magneticLabels.size()) magneticLabels.push_back(m->sensorLabel);
                magnetic.push_back({t, m->sensorPose.translation(), m->magnitude(), label});
            }
            engine->process(obs);
            if (options.onProgress) {
                options.onProgress(engine->graph().nodes.size(),
                                   engine->optimizer().loopClosures().size());
            }
            const double fraction =
                fractionRead ? fractionRead()
                : simulator  ? dataSeconds / std::min(simulator->duration(), options.maxSeconds)
                             : 0.0;  // live: no end known
            progress.update(fraction, dataSeconds);
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
        engine->finish();
    } catch (const std::exception& e) {
        err << "lodestone-slam: error while finishing: " << e.what() << "\n";
        result.exitCode = 1;
        if (result.error.empty()) result.error = e.what();
    }
    if (result.error.empty() && engine->graph().nodes.empty()) {
        // Exit 0 with an empty map would read as success.
        result.error = "the run made no nodes: the node decider got no motion from the " +
                       std::to_string(engine->stats().observations) + " observations (" +
                       std::to_string(engine->stats().frames) +
                       " RGB-D frames) - is this the recording the configured deciders need?";
        result.exitCode = 1;
        err << "lodestone-slam: error: " << result.error << "\n";
    }
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    progress.finish(dataSeconds);
    if (simTruth) simTruth->close();  // the truth of what was run, even if it stopped early

    // --- Outputs -----------------------------------------------------------------------------------
    try {
        const auto& graph = engine->graph();
        const auto& closures = engine->optimizer().loopClosures();
        result.nodes = graph.nodes.size();
        result.loopClosures = closures.size();
        const std::string trajectory = (dir / "trajectory.tum").string();
        graphslam::writeNodeTrajectory(trajectory, graph, engine->nodes());
        graph.saveToTextFile((dir / "graph.graph").string());
        graphslam::writeClosureLog((dir / "closures.csv").string(), *engine);
        graphslam::writeNodeTable((dir / "nodes.csv").string(), engine->nodes(),
                                  engine->stats().nodeMs);
        const auto& beforeKidnap = engine->relocalizer().mapAtFirstKidnap();
        if (!beforeKidnap.empty()) {
            // What the map was when the first kidnap began: lodestone-eval relocation compares
            // it with the end of the run (what relocations did to the map).
            io::TumTrajectoryWriter w((dir / "map_at_first_kidnap.tum").string());
            for (const auto& [id, pose] : beforeKidnap) w.write(engine->nodes().at(id).timestamp, pose);
            w.close();
        }
        const std::size_t mapPoints =
            graphslam::writeMapPly((dir / "map.ply").string(), graph, engine->nodes());
        cv::imwrite((dir / "graph.png").string(), plotGraph(graph, closures));
        if (!magnetic.empty()) {
            eval::FieldMapBuilder fieldMap(nodeTrajectory(*engine), kFieldMapCell);
            for (const auto& r : magnetic) {
                fieldMap.add(r.time, r.sensorOffset, r.magnitude, magneticLabels[r.label]);
            }
            cv::imwrite((dir / "field_map.png").string(),
                        fieldMap.render("|B| on the optimized trajectory"));
        }

        JsonObject report;
        report.set("tool", "lodestone-slam");
        JsonObject input;
        input.set(options.live ? "live" : options.scenario.empty() ? "rawlog" : "scenario",
                  options.live ? options.live->name()
                  : options.scenario.empty() ? options.rawlog : options.scenario)
            .set("config", options.config)
            .set("max_seconds", options.maxSeconds)
            .set("decode_ahead", options.decodeAhead)
            .set("decode_threads", decodeThreads);
        report.set("input", input);
        report.set("engine", engine->describe());
        JsonObject timing = timingJson(engine->stats(), wall, dataSeconds, sourceSeconds,
                                       engine->stats().observations);
        if (prefetcher) {
            // The workers' CPU time: what reading and decoding cost, off the frame loop.
            const auto w = prefetcher->workerTime();
            timing.set("worker_read_s", w.readSeconds).set("worker_decode_s", w.decodeSeconds);
        }
        report.set("timing", timing);
        report.set("map_points", mapPoints);

        const std::string gtPath =
            simulator ? (dir / "ground_truth.tum").string() : options.groundTruth;
        if (!gtPath.empty()) {
            const auto est = nodeTrajectory(*engine);
            const auto gt = io::readTumTrajectory(gtPath);
            const auto ate = eval::absoluteTrajectoryError(est, gt);
            if (ate.pairs >= 3) {
                result.ateRmse = ate.rmse;
                report.set("ate", JsonObject()
                                      .set("ground_truth", gtPath)
                                      .set("pairs", ate.pairs)
                                      .set("rmse_m", ate.rmse)
                                      .set("mean_m", ate.mean)
                                      .set("median_m", ate.median)
                                      .set("max_m", ate.max));
                cv::imwrite((dir / "trajectory.png").string(), eval::plotTrajectories(est, gt, ate));
            } else {
                err << "lodestone-slam: warning: only " << ate.pairs << " nodes match "
                    << gtPath << " in time; no ATE\n";
            }
        }
        if (!result.error.empty()) report.set("error", result.error);
        // Written last and whole: a report.json there means every output above was written.
        const fs::path partial = dir / "report.json.partial";
        {
            std::ofstream json(partial);
            report.write(json);
            json << "\n";
            if (!json) throw std::runtime_error(partial.string() + ": write failed");
        }
        fs::rename(partial, dir / "report.json");

        std::size_t rejected = 0;
        for (const auto& lc : closures) rejected += lc.rejected;
        char line[256];
        std::snprintf(line, sizeof line,
                      "lodestone-slam: %zu nodes, %zu loop closures (%zu rejected), %zu frames, "
                      "%.1f s of data in %.1f s (%.2fx real time)\n",
                      result.nodes, result.loopClosures, rejected, engine->stats().frames,
                      dataSeconds, wall, wall > 0 ? dataSeconds / wall : 0.0);
        out << line;
        if (result.ateRmse) {
            std::snprintf(line, sizeof line, "ATE RMSE %.4f m over %zu nodes (ground truth %s)\n",
                          *result.ateRmse, result.nodes, gtPath.c_str());
            out << line;
        }
        out << "outputs in " << dir.string()
            << ": trajectory.tum graph.graph closures.csv nodes.csv map.ply report.json graph.png"
            << (result.ateRmse ? " trajectory.png" : "") << (simulator ? " ground_truth.tum events.txt" : "")
            << (beforeKidnap.empty() ? "" : " map_at_first_kidnap.tum")
            << (magnetic.empty() ? "" : " field_map.png")
            << "\n";
    } catch (const std::exception& e) {
        err << "lodestone-slam: error writing outputs: " << e.what() << "\n";
        result.exitCode = 1;
        if (result.error.empty()) result.error = e.what();
    }
    return result;
}

}  // namespace lodestone::slamapp
