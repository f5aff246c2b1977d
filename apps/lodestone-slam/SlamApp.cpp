#include <SlamApp.h>
#include <lodestone/config/CommandLine.h>
#include <lodestone/obs/MagneticUnit.h>
#include <lodestone/slamapp/SlamRun.h>

#include <filesystem>

namespace lodestone::slamapp {

namespace {
/** lodestone-slam's command line: its arguments, what goes together, the run's options. */
struct SlamArguments {
    explicit SlamArguments(TCLAP::CmdLine& cmd);
    /** Why these arguments do not make a run ("" if they do). */
    std::string usageError();
    SlamRunOptions options(bool terminal);

    TCLAP::ValueArg<std::string> rawlog;
    TCLAP::ValueArg<std::string> sim;
    TCLAP::ValueArg<std::string> config;
    TCLAP::ValueArg<std::string> outDir;
    TCLAP::ValueArg<std::string> gt;
    TCLAP::ValueArg<std::string> mapOut;
    TCLAP::ValueArg<double> mapEvery;
    TCLAP::ValueArg<std::string> mapIn;
    TCLAP::ValueArg<std::string> mode;
    TCLAP::ValueArg<double> maxSeconds;
    TCLAP::ValueArg<int> decodeAhead;
    TCLAP::ValueArg<int> decodeThreads;
    TCLAP::ValueArg<std::string> magneticUnit;
    TCLAP::SwitchArg quiet;
    TCLAP::SwitchArg viewArg;
    TCLAP::SwitchArg meshArg;
};

SlamArguments::SlamArguments(TCLAP::CmdLine& cmd)
    : rawlog("r", "rawlog", "input rawlog (.rawlog or .rawlog.gz)", false, "", "FILE", cmd),
      sim("s", "sim", "run the simulator on this scenario instead", false, "", "SCENARIO.ini", cmd),
      config("c", "config", "SLAM configuration (config_ini/*.ini)", true, "", "INI", cmd),
      outDir("o", "out", "output directory (created)", true, "", "DIR", cmd),
      gt("g", "ground-truth", "TUM ground truth for the ATE", false, "", "GT.tum", cmd),
      mapOut("", "map-out",
             "save the map at the end in this folder (replaced whole; lodestone-inspect map DIR "
             "describes it)",
             false, "", "DIR", cmd),
      mapEvery("", "map-every",
               "with --map-out: also save the map every S seconds of data (each time whole, so a "
               "crash leaves the last one)",
               false, 0, "S", cmd),
      mapIn("", "map-in",
            "start in this saved map (lodestone-slam --map-out): relocalize in it, then track "
            "against it",
            false, "", "DIR", cmd),
      mode("", "mode",
           "with --map-in: localize (the map is held fixed) or extend (the run's new places join "
           "the map, which later closures may correct; written back with --map-out)",
           false, "localize", "MODE", cmd),
      maxSeconds("", "max-seconds", "process only this much data [s]", false, 0, "S", cmd),
      decodeAhead("", "decode-ahead",
                  "frames (observations with images or range data) read and decoded ahead on other "
                  "threads (0: in the frame loop; results are the same)",
                  false, 8, "N", cmd),
      decodeThreads("", "decode-threads",
                    "threads that read and decode ahead (0: one per core this process may use)",
                    false, 0, "N", cmd),
      magneticUnit("", "magnetic-unit",
                   "the unit the rawlog's magnetometer numbers are in, if not microtesla (a rawlog "
                   "written by another tool): gauss|uT|T|normalized:<field strength in uT>",
                   false, "", "UNIT", cmd),
      quiet("q", "quiet", "no progress output", cmd),
      viewArg("", "view",
              "MRPT's 3D window with the run as it goes (graph by segment, closures by closer, the "
              "field, the current pose; keys: space pauses, s steps, v follows, q closes); at a "
              "terminal it stays open at the end until closed",
              cmd),
      meshArg("", "mesh",
              "the dense model: every keyframe's frame fused at its optimized pose (TSDF, [dense] "
              "keys of the INI) and meshed into mesh.ply - after the run, or as it goes with "
              "[dense] fusion = while_running (and live)",
              cmd) {}

std::string SlamArguments::usageError() {
    std::string usage;
    if (usage.empty() && rawlog.isSet() == sim.isSet())
        usage = "give exactly one of --rawlog and --sim";
    if (usage.empty() && sim.isSet() && gt.isSet()) {
        usage = "--ground-truth is for --rawlog; --sim uses the simulator's own ground truth";
    }
    if (usage.empty() && mapOut.isSet() &&
        (mapOut.getValue().empty() || std::filesystem::weakly_canonical(mapOut.getValue()) ==
                                          std::filesystem::weakly_canonical(outDir.getValue()))) {
        usage = "--map-out needs a folder of its own (not --out's)";
    }
    if (usage.empty() && mode.isSet() && !mapIn.isSet()) usage = "--mode is for --map-in";
    if (usage.empty() && mapEvery.isSet() && (!mapOut.isSet() || !(mapEvery.getValue() > 0))) {
        usage = "--map-every needs --map-out and a number of seconds > 0";
    }
    if (usage.empty() && mapIn.isSet() && mapOut.isSet() && mode.getValue() != "extend") {
        usage = "--map-out with --map-in: give --mode extend (localize leaves the map as it is)";
    }
    if (usage.empty() && mode.getValue() == "extend" && !mapOut.isSet()) {
        usage = "--mode extend: give --map-out (where the extended map goes)";
    }
    if (usage.empty() && mode.getValue() != "localize" && mode.getValue() != "extend") {
        usage = "--mode " + mode.getValue() + ": localize or extend";
    }
    if (usage.empty() && maxSeconds.isSet() && !(maxSeconds.getValue() > 0)) {
        usage = "--max-seconds must be > 0";
    }
    if (usage.empty() && (decodeAhead.getValue() < 0 || decodeAhead.getValue() > 1000)) {
        usage = "--decode-ahead must be 0..1000";
    }
    if (usage.empty() && (decodeThreads.getValue() < 0 || decodeThreads.getValue() > 64)) {
        usage = "--decode-threads must be 0..64";
    }
    if (usage.empty() && magneticUnit.isSet() && !rawlog.isSet()) {
        usage = "--magnetic-unit is for --rawlog (the simulator writes microtesla)";
    }
    if (usage.empty() && magneticUnit.isSet()) {
        try {
            obs::MagneticUnit::parse(magneticUnit.getValue());
        } catch (const std::invalid_argument& e) {
            usage = std::string("--magnetic-unit: ") + e.what();
        }
    }
    return usage;
}

SlamRunOptions SlamArguments::options(bool terminal) {
    SlamRunOptions o;
    o.rawlog = rawlog.getValue();
    o.scenario = sim.getValue();
    o.config = config.getValue();
    o.outDir = outDir.getValue();
    o.groundTruth = gt.getValue();
    o.mapOut = mapOut.getValue();
    o.mapEvery = mapEvery.getValue();
    o.mapIn = mapIn.getValue();
    o.extendMap = mode.getValue() == "extend";
    if (maxSeconds.isSet()) o.maxSeconds = maxSeconds.getValue();
    o.decodeAhead = static_cast<std::size_t>(decodeAhead.getValue());
    o.decodeThreads = static_cast<std::size_t>(decodeThreads.getValue());
    o.quiet = quiet.getValue();
    o.terminal = terminal;
    o.view = viewArg.getValue();
    o.mesh = meshArg.getValue();
    o.viewKeepOpen = terminal;
    o.magneticUnit = magneticUnit.getValue();
    return o;
}
}  // namespace

int runSlamApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err,
               bool terminal) {
    TCLAP::CmdLine cmd(
        "Offline graph SLAM (RGB-D + wheel odometry + magnetometers) on a rawlog or a simulated "
        "scenario",
        ' ', "");
    SlamArguments args(cmd);  // (TCLAP reads its values through non-const getters)
    const auto outcome = config::parseCommandLine(cmd, std::vector<std::string>(argv, argv + argc));
    if (outcome.kind == config::ParseOutcome::Kind::HelpShown) return 0;
    std::string usage = outcome.error;
    if (usage.empty()) usage = args.usageError();
    if (!usage.empty()) {
        err << "lodestone-slam: " << usage << " (see lodestone-slam --help)\n";
        return 2;
    }
    return runSlam(args.options(terminal), out, err).exitCode;
}

}  // namespace lodestone::slamapp
