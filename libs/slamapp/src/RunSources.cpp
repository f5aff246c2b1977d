#include "RunParts.h"

#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/DeciderRegistry.h>
#include <lodestone/io/KidnapEvents.h>
#include <lodestone/io/RawlogPaths.h>
#include <lodestone/dense/DenseParams.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/obs/MagneticUnit.h>
#include <lodestone/outputs/RunFiles.h>
#include <lodestone/sim/RobotConfig.h>
#include <mrpt/config/CConfigFile.h>

#include <algorithm>
#include <deque>
#include <filesystem>
#include <thread>

#include <sched.h>

namespace lodestone::slamapp::detail {

namespace {

namespace fs = std::filesystem;
using outputs::RunFile;

// How far into a rawlog to look for the observation classes the deciders need: every sensor
// of a recording shows up within its first seconds.
constexpr std::size_t kPrescanObservations = 3000;
// Magnetometer readings whose median magnitude must be Earth's field, where the deciders take
// magnetometers (within the prescan's reach): a few seconds of any magnetometer.
constexpr std::size_t kPlausibilityReadings = 100;

std::string join(const std::set<std::string>& items) {
    std::string out;
    for (const auto& i : items) out += (out.empty() ? "" : ", ") + i;
    return out;
}

/** A rawlog whose first observations were read to check that the deciders' observation
 * classes are there (until each has shown up) and, where they take magnetometers, that the
 * field is Earth's in microtesla (the first kPlausibilityReadings readings), then handed out
 * again before the rest: the file is opened and read once. Magnetometer readings are converted
 * from `unit` as they are read. */
class PrescannedRawlog : public io::DataSource {
  public:
    /** Throws InputError naming the classes missing from the first kPrescanObservations, or
     * the rawlog and --magnetic-unit when the field is implausible. */
    PrescannedRawlog(const std::string& path, const std::set<std::string>& required,
                     const obs::MagneticUnit& unit)
        : source_(path), unit_(unit) {
        std::set<std::string> missing = required, classes;
        const bool magnetic = required.count("CObservationMagnetometer") > 0;
        std::vector<double> magnitudes;
        while ((!missing.empty() || (magnetic && magnitudes.size() < kPlausibilityReadings)) &&
               ahead_.size() < kPrescanObservations) {
            auto obs = next();
            if (!obs) break;
            if (const auto* m = dynamic_cast<const obs::CObservationMagnetometer*>(obs.get()))
                magnitudes.push_back(m->magnitude());
            // MRPT names classes with their namespace; deciders ask by the bare class name.
            const std::string name = obs->GetRuntimeClass()->className;
            const auto colons = name.rfind("::");
            const std::string bare = colons == std::string::npos ? name : name.substr(colons + 2);
            missing.erase(bare);
            classes.insert(bare);
            if (bare == "CObservationMagnetometer") magnetometers_.insert(obs->sensorLabel);
            ahead_.push_back(std::move(obs));
        }
        if (!missing.empty()) {
            // RGB-D frames and no wheels: a camera-only recording, which has its own INI.
            const bool cameraOnly = missing.count("CObservationOdometry") &&
                                    classes.count("CObservation3DRangeScan");
            throw InputError(
                path + ": no " + join(missing) + " among its first " +
                std::to_string(ahead_.size()) + " observations; the configured deciders need " +
                join(required) +
                (cameraOnly ? ". A camera-only recording (RGB-D, no wheel odometry) runs "
                              "with config_ini/slam/rgbd_only.ini"
                            : ""));
        }
        if (const auto why = obs::implausibleFieldMagnitude(std::move(magnitudes))) {
            throw InputError(path + ": its magnetometers, read as " + unit_.name + ": " + *why +
                             "; give the unit they are in with --magnetic-unit " +
                             obs::kMagneticUnitChoices);
        }
        prescanned_ = true;
    }

    mrpt::obs::CObservation::Ptr next() override {
        if (!prescanned_ || ahead_.empty()) return converted(source_.next());
        auto obs = std::move(ahead_.front());
        ahead_.pop_front();
        return obs;
    }
    std::string name() const override { return source_.name(); }
    double fractionRead() const { return source_.fractionRead(); }
    /** The magnetometers' labels among the observations read ahead. */
    const std::set<std::string>& magnetometers() const { return magnetometers_; }

  private:
    /** A magnetometer's reading in microtesla. */
    mrpt::obs::CObservation::Ptr converted(mrpt::obs::CObservation::Ptr obs) const {
        if (unit_.microteslaPerUnit == 1.0) return obs;
        if (auto* m = dynamic_cast<obs::CObservationMagnetometer*>(obs.get())) {
            m->field *= unit_.microteslaPerUnit;
            m->noiseStd *= unit_.microteslaPerUnit;
        }
        return obs;
    }

    io::RawlogSource source_;
    obs::MagneticUnit unit_;
    bool prescanned_{false};
    std::set<std::string> magnetometers_;
    std::deque<mrpt::obs::CObservation::Ptr> ahead_;
};

/** The cores this process may run on (taskset / cgroup affinity), not the machine's. */
std::size_t usableCores() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof(set), &set) == 0) {
        return std::max(1, CPU_COUNT(&set));
    }
    return std::max(1u, std::thread::hardware_concurrency());
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

/** The rawlog, read and decoded ahead on worker threads unless decodeAhead is 0. */
void openRawlog(const SlamRunOptions& options, RunInputs& in) {
    if (!fs::exists(options.rawlog)) throw InputError("cannot open rawlog '" + options.rawlog + "'");
    obs::MagneticUnit unit;
    try {
        if (!options.magneticUnit.empty()) unit = obs::MagneticUnit::parse(options.magneticUnit);
    } catch (const std::invalid_argument& e) {
        throw InputError(std::string("--magnetic-unit: ") + e.what());
    }
    auto rawlog = std::make_unique<PrescannedRawlog>(options.rawlog,
                                                     in.engine->requiredObservations(), unit);
    const PrescannedRawlog* inner = rawlog.get();
    in.prescannedMagnetometers = inner->magnetometers();
    if (options.decodeAhead == 0) {
        in.fractionRead = [inner] { return inner->fractionRead(); };
        in.source = std::move(rawlog);
        return;
    }
    in.decodeThreads = options.decodeThreads > 0 ? options.decodeThreads : usableCores();
    // The workers also prepare the node decider's frames (RGB-D features): the engine must
    // outlive the source (RunInputs destroys the source first).
    auto prefetch = std::make_unique<io::PrefetchingSource>(
        std::move(rawlog), options.decodeAhead, [inner] { return inner->fractionRead(); },
        in.decodeThreads, in.engine->preparer(options.decodeAhead + 1));
    const io::PrefetchingSource* p = prefetch.get();
    in.prefetcher = p;
    in.fractionRead = [p] { return p->progress(); };
    in.source = std::move(prefetch);
}

}  // namespace

std::set<std::string> allowedSections() {
    std::set<std::string> s{"graphslam",       "relocalization",  "kidnap_detection",
                            "wheel_odometry",  "visual_odometry", "odometry_fusion",
                            "dense"};
    const auto& reg = graphslam::DeciderRegistry::instance();
    for (const auto& names : {reg.nodeDeciders(), reg.edgeDeciders(), reg.optimizers()}) {
        s.insert(names.begin(), names.end());
    }
    return s;
}

RunInputs openInputs(const SlamRunOptions& options) {
    RunInputs in;
    if (!fs::exists(options.config)) throw InputError("cannot open configuration file '" + options.config + "'");
    const mrpt::config::CConfigFile ini(options.config);
    config::checkSections(ini, allowedSections(), options.config);
    // The INI as written, first: its mistakes are named before a scenario's, and its own
    // [wheel_odometry] keys are checked even where a scenario's replace them below.
    in.engine = graphslam::SlamEngine::fromConfig(ini);
    if (options.mesh || ini.sectionExists("dense")) (void)dense::DenseParams::read(ini);  // (named now, not after the run)
    if (options.live) {
        in.source = std::make_unique<SharedSource>(options.live);
    } else if (!options.scenario.empty()) {
        const auto scenario = sim::Scenario::load(options.scenario);
        // The simulated robot's wheels are the scenario's, whatever the INI says: the engine
        // again (10-20 ms once: a start that builds one against one that stops before), from the
        // INI with them in [wheel_odometry].
        in.engine = graphslam::SlamEngine::fromConfig(
            sim::withScenarioWheels(ini, scenario, options.config));
        auto simulator = std::make_unique<sim::SimulatorSource>(scenario, scenario.seed);
        in.simulator = simulator.get();
        in.source = std::move(simulator);
    } else {
        openRawlog(options, in);
    }
    if (!options.mapIn.empty()) {
        in.mapSessions =
            loadMap(options, configText(options), *in.engine, in.prescannedMagnetometers);
    }
    if (!options.groundTruth.empty()) {
        if (!fs::exists(options.groundTruth)) {
            throw InputError("cannot open ground truth '" + options.groundTruth + "'");
        }
        // Read now, not after the run: a bad line is named before any work. The deciders
        // may report their diagnostics against it.
        in.engine->setDiagnosticTruth(std::make_shared<const std::vector<io::TumPose>>(
            io::readTumTrajectory(options.groundTruth)));
    }
    const fs::path dir(options.outDir);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) {
        throw InputError("cannot create output directory '" + options.outDir + "': " + ec.message());
    }
    // A previous run's outputs must not stay beside this one's if this one stops early.
    for (const auto& file : outputs::runFiles()) {
        fs::remove(dir / file.name, ec);
        fs::remove(io::partialPath((dir / file.name).string()), ec);
    }
    if (in.simulator) {
        in.simTruth = std::make_unique<io::TumTrajectoryWriter>(
            outputs::pathIn(options.outDir, RunFile::GroundTruth));
        io::writeKidnapEvents(outputs::pathIn(options.outDir, RunFile::Events),
                              in.simulator->scenario().name, sim::kidnapRecords(*in.simulator));
    }
    return in;
}

}  // namespace lodestone::slamapp::detail
