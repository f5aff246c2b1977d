#include <lodestone/config/CommandLine.h>
#include <lodestone/config/IniSection.h>
#include <GrabApp.h>
#include <lodestone/grab/GrabSession.h>
#include <mrpt/system/os.h>

#include <atomic>
#include <csignal>
#include <cstdlib>

namespace lodestone::grab {

namespace {
std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");

extern "C" void onStopSignal(int) { g_stop.store(true); }

void installStopHandlers() {
    struct sigaction sa {};
    sa.sa_handler = onStopSignal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND;  // a second Ctrl-C ends the process the default way
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}
}  // namespace

int runGrabApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err,
               bool terminal) {
    TCLAP::CmdLine cmd(
        "Grab MRPT hwdrivers sensors (and Lodestone's) into a rawlog, in time order, flushed as "
        "it goes; rawlog-grabber's INI conventions",
        ' ', "");
    TCLAP::UnlabeledValueArg<std::string> ini("GRAB_INI", "[global] and a section per sensor "
                                              "with driver = <class>", true, "", "GRAB.ini", cmd);
    TCLAP::ValueArg<std::string> prefix("o", "out", "output prefix: PREFIX.rawlog.gz and "
                                        "PREFIX_Images/ (default: [global] rawlog_prefix)",
                                        false, "", "PREFIX", cmd);
    TCLAP::ValueArg<double> duration("", "duration", "stop after S seconds", false, 0, "S", cmd);
    TCLAP::MultiArg<std::string> plugins("p", "plugin", "load a module that registers more "
                                         "drivers or classes (as rawlog-grabber -p)",
                                         false, "LIB", cmd);
    TCLAP::ValueArg<std::string> slam("", "slam", "run SLAM live on the stream with this "
                                      "lodestone-slam INI", false, "", "SLAM.ini", cmd);
    TCLAP::ValueArg<std::string> slamOut("", "slam-out", "live SLAM's outputs (default "
                                         "PREFIX_slam)", false, "", "DIR", cmd);
    TCLAP::ValueArg<std::string> mapIn("", "map-in", "live SLAM starts in this saved map "
                                       "(lodestone-slam --map-out) and localizes in it",
                                       false, "", "DIR", cmd);
    TCLAP::ValueArg<double> maxLag("", "max-lag", "live SLAM skips RGB-D frames while this many "
                                   "seconds behind the newest observation (default 0.3)",
                                   false, 0.3, "S", cmd);
    TCLAP::SwitchArg view("", "view", "live SLAM in MRPT's 3D window (as lodestone-slam --view)", cmd);
    TCLAP::SwitchArg mesh("", "mesh",
                          "live SLAM fuses its keyframes into a dense model as it goes, re-fused where the graph "
                          "moves them: mesh.ply in the SLAM outputs ([dense] keys of the INI)",
                          cmd);
    TCLAP::SwitchArg quiet("q", "quiet", "no status line", cmd);
    std::vector<std::string> words(argv, argv + argc);
    const auto outcome = config::parseCommandLine(cmd, words);
    if (outcome.kind == config::ParseOutcome::Kind::UsageError) {
        err << "lodestone-grab: " << outcome.error << "\n(see lodestone-grab --help)\n";
        return 2;
    }
    if (outcome.kind != config::ParseOutcome::Kind::Run) return 0;
    if (duration.isSet() && !(duration.getValue() > 0)) {
        err << "lodestone-grab: --duration: must be > 0 s\n";
        return 2;
    }
    for (const auto& lib : plugins.getValue()) {
        std::string errors;
        if (!mrpt::system::loadPluginModule(lib, errors)) {
            err << "lodestone-grab: error: --plugin " << lib << ": " << errors << "\n";
            return 1;
        }
    }
    GrabOptions options;
    options.config = ini.getValue();
    options.out = prefix.getValue();
    if (duration.isSet()) options.duration = duration.getValue();
    if (!(maxLag.getValue() > 0)) {
        err << "lodestone-grab: --max-lag: must be > 0 s\n";
        return 2;
    }
    if ((slamOut.isSet() || mapIn.isSet() || view.isSet() || mesh.isSet()) && !slam.isSet()) {
        err << "lodestone-grab: --slam-out, --map-in, --view and --mesh need --slam\n";
        return 2;
    }
    if (view.getValue() && !std::getenv("DISPLAY"))
        err << "lodestone-grab: --view: no display (DISPLAY is not set): SLAM runs without the view\n";
    options.slamConfig = slam.getValue();
    options.slamOut = slamOut.getValue();
    options.slamMapIn = mapIn.getValue();
    options.maxLag = maxLag.getValue();
    options.slamView = view.getValue();
    options.slamMesh = mesh.getValue();
    options.quiet = quiet.getValue();
    options.terminal = terminal;
    g_stop = false;
    installStopHandlers();
    try {
        return runGrab(options, g_stop, out, err).exitCode;
    } catch (const std::exception& e) {
        err << "lodestone-grab: error: " << e.what() << "\n";
        return 1;
    }
}

}  // namespace lodestone::grab
