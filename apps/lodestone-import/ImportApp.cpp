#include <lodestone/config/CommandLine.h>
#include <ImportApp.h>
#include <lodestone/io/RawlogPaths.h>
#include <lodestone/datasets/MagneticRecordingImport.h>
#include <lodestone/datasets/SevenScenesImport.h>
#include <lodestone/datasets/TumRgbdImport.h>
#include <lodestone/obs/MagneticUnit.h>
#include <lodestone/obs/registerAllClasses.h>

#include <vector>

namespace lodestone::datasets {

namespace {
// Depth-to-colour registration, the same two options for every RGB-D importer.
struct RegistrationArgs {
    TCLAP::ValueArg<std::string> depthIntrinsics, depthToColour;
    explicit RegistrationArgs(TCLAP::CmdLine& cmd)
        : depthIntrinsics("", "depth-intrinsics",
                          "depth not registered to colour: the depth camera's fx,fy,cx,cy (with "
                          "--depth-to-colour)",
                          false, "", "K", cmd),
          depthToColour("", "depth-to-colour",
                        "the depth camera's pose in the colour camera's optical frame: "
                        "tx,ty,tz,qx,qy,qz,qw [m] (with --depth-intrinsics)",
                        false, "", "POSE", cmd) {}
    /** Throws std::invalid_argument naming the option. */
    std::optional<DepthRegistration> parse() {
        if (depthIntrinsics.getValue().empty() && depthToColour.getValue().empty()) return {};
        if (depthIntrinsics.getValue().empty() || depthToColour.getValue().empty())
            throw std::invalid_argument("--depth-intrinsics and --depth-to-colour go together");
        DepthRegistration r;
        try {
            r.depth = TumIntrinsics::parse(depthIntrinsics.getValue());
        } catch (const std::invalid_argument& e) {
            throw std::invalid_argument(std::string("--depth-intrinsics: ") + e.what());
        }
        try {
            r.colourFromDepth = DepthRegistration::parsePose(depthToColour.getValue());
        } catch (const std::invalid_argument& e) {
            throw std::invalid_argument(std::string("--depth-to-colour: ") + e.what());
        }
        return r;
    }
};

int importTum(const std::vector<std::string>& words, std::ostream& out, std::ostream& err) {
    TCLAP::CmdLine cmd("Convert a TUM RGB-D sequence folder into a rawlog (+ OUT.gt.tum)", ' ', "");
    TCLAP::UnlabeledMultiArg<std::string> positional(
        "DIR_OUT", "DIR (the sequence: rgb.txt, depth.txt, groundtruth.txt) then OUT.rawlog", true,
        "DIR OUT", cmd);
    TCLAP::ValueArg<std::string> intrinsics(
        "", "intrinsics", "fr1, fr2, fr3, default or fx,fy,cx,cy", false, "fr1", "K", cmd);
    TCLAP::ValueArg<double> maxDt("", "max-dt", "RGB-depth association tolerance [s]", false, 0.02,
                                  "S", cmd);
    TCLAP::ValueArg<double> depthScale("", "depth-scale",
                                       "depth image units per metre (TUM 5000, 7-Scenes / ICL-NUIM 1000)",
                                       false, 5000.0, "U", cmd);
    RegistrationArgs registration(cmd);
    const auto outcome = config::parseCommandLine(cmd, words);
    if (outcome.kind == config::ParseOutcome::Kind::HelpShown) return 0;
    const auto usage = [&](const std::string& why) {
        err << "lodestone-import tum: " << why << " (see lodestone-import tum --help)\n";
        return 2;
    };
    if (outcome.kind == config::ParseOutcome::Kind::UsageError) return usage(outcome.error);
    if (positional.getValue().size() != 2) return usage("expected DIR and OUT");
    TumImportOptions o;
    try {
        o.intrinsics = TumIntrinsics::parse(intrinsics.getValue());
    } catch (const std::invalid_argument& e) {
        return usage(std::string("--intrinsics: ") + e.what());
    }
    try {
        o.registration = registration.parse();
    } catch (const std::invalid_argument& e) {
        return usage(e.what());
    }
    o.maxTimeDifference = maxDt.getValue();
    if (!(depthScale.getValue() > 0)) return usage("--depth-scale must be > 0");
    o.depthScale = depthScale.getValue();
    const auto r = importTumRgbd(positional.getValue()[0], positional.getValue()[1], o);
    out << r.frames << " RGB-D frames -> " << r.rawlog << " (" << r.unmatchedRgb << " colour and "
        << r.unmatchedDepth << " depth images without a partner)\n";
    if (!r.groundTruth.empty()) {
        out << r.groundTruthPoses << " ground-truth poses -> " << r.groundTruth << "\n";
    }
    return 0;
}
int importSevenScenes(const std::vector<std::string>& words, std::ostream& out, std::ostream& err) {
    TCLAP::CmdLine cmd("Convert a 7-Scenes / 3DMatch sequence folder into a rawlog (+ OUT.gt.tum)",
                       ' ', "");
    TCLAP::UnlabeledMultiArg<std::string> positional(
        "DIR_OUT", "DIR (frame-NNNNNN.color.png, .depth.png, .pose.txt) then OUT.rawlog", true,
        "DIR OUT", cmd);
    TCLAP::ValueArg<std::string> intrinsics(
        "", "intrinsics", "fx,fy,cx,cy (default: camera-intrinsics.txt beside, else 585,585,320,240)",
        false, "", "K", cmd);
    TCLAP::ValueArg<double> depthScale("", "depth-scale", "depth image units per metre", false,
                                       1000.0, "U", cmd);
    TCLAP::ValueArg<double> rate("", "rate", "frame rate [Hz]: frame i is at i / rate", false, 30.0,
                                 "HZ", cmd);
    RegistrationArgs registration(cmd);
    const auto outcome = config::parseCommandLine(cmd, words);
    if (outcome.kind == config::ParseOutcome::Kind::HelpShown) return 0;
    const auto usage = [&](const std::string& why) {
        err << "lodestone-import 7scenes: " << why << " (see lodestone-import 7scenes --help)\n";
        return 2;
    };
    if (outcome.kind == config::ParseOutcome::Kind::UsageError) return usage(outcome.error);
    if (positional.getValue().size() != 2) return usage("expected DIR and OUT");
    SevenScenesImportOptions o;
    if (!intrinsics.getValue().empty()) {
        try {
            o.intrinsics = TumIntrinsics::parse(intrinsics.getValue());
        } catch (const std::invalid_argument& e) {
            return usage(std::string("--intrinsics: ") + e.what());
        }
    }
    if (!(depthScale.getValue() > 0)) return usage("--depth-scale must be > 0");
    if (!(rate.getValue() > 0)) return usage("--rate must be > 0");
    try {
        o.registration = registration.parse();
    } catch (const std::invalid_argument& e) {
        return usage(e.what());
    }
    o.depthScale = depthScale.getValue();
    o.rate = rate.getValue();
    const auto r = importSevenScenes(positional.getValue()[0], positional.getValue()[1], o);
    out << r.frames << " RGB-D frames -> " << r.rawlog << " (intrinsics " << r.intrinsics.fx << ", "
        << r.intrinsics.fy << ", " << r.intrinsics.cx << ", " << r.intrinsics.cy << " from "
        << r.intrinsicsSource << ")\n"
        << r.groundTruthPoses << " ground-truth poses -> " << r.groundTruth << "\n";
    return 0;
}

// The drift-model options shared by the magnetometer recordings (Kok & Solin's defaults).
struct DriftArgs {
    TCLAP::ValueArg<std::uint64_t> seed;
    TCLAP::ValueArg<double> bias, sp2, sh2, rate;
    explicit DriftArgs(TCLAP::CmdLine& cmd)
        : seed("", "seed", "odometry noise seed", false, 1, "N", cmd),
          bias("", "bias", "heading rate bias [rad/s]", false, 0.005, "RAD_S", cmd),
          sp2("", "sp2", "position noise variance per odometry sample [m^2]", false, 1e-4, "M2",
              cmd),
          sh2("", "sh2", "heading noise variance per odometry sample [rad^2]", false, 1e-4, "RAD2",
              cmd),
          rate("", "odometry-rate", "odometry samples per second (0: one per magnetometer sample)",
               false, 10, "HZ", cmd) {}
    OdometryDriftModel model() {
        OdometryDriftModel m;
        m.seed = seed.getValue();
        m.bias = bias.getValue();
        m.sp2 = sp2.getValue();
        m.sh2 = sh2.getValue();
        m.rate = rate.getValue();
        return m;
    }
};

void printMagneticImport(const MagneticImportResult& r, std::ostream& out) {
    out << r.magnetometerSamples << " magnetometer and " << r.odometrySamples
        << " odometry samples (" << r.duration << " s, " << r.pathLength << " m) -> " << r.rawlog
        << "\nground truth -> " << r.groundTruth << "\n";
}

int importMagnetic(const std::string& kind, const std::vector<std::string>& words,
                   std::ostream& out, std::ostream& err) {
    const bool aalto = kind == "aalto";
    TCLAP::CmdLine cmd(aalto ? "Convert an Aalto invensense trial (N-time/loc/mag.csv) into a "
                               "rawlog with synthesized odometry (+ OUT.gt.tum)"
                             : "Convert a Kok & Solin walk CSV into a rawlog with synthesized "
                               "odometry (+ OUT.gt.tum)",
                       ' ', "");
    TCLAP::UnlabeledMultiArg<std::string> positional(
        "ARGS", aalto ? "DIR TRIAL OUT.rawlog" : "FILE.csv OUT.rawlog", true,
        aalto ? "DIR TRIAL OUT" : "FILE OUT", cmd);
    DriftArgs drift(cmd);
    TCLAP::ValueArg<std::string> unitArg(
        "", "unit",
        std::string("the field's unit in the files (both datasets document uT): ") +
            obs::kMagneticUnitChoices,
        false, "uT", "UNIT", cmd);
    const auto outcome = config::parseCommandLine(cmd, words);
    if (outcome.kind == config::ParseOutcome::Kind::HelpShown) return 0;
    const auto usage = [&](const std::string& why) {
        err << "lodestone-import " << kind << ": " << why << " (see lodestone-import " << kind
            << " --help)\n";
        return 2;
    };
    if (outcome.kind == config::ParseOutcome::Kind::UsageError) return usage(outcome.error);
    obs::MagneticUnit unit;
    try {
        unit = obs::MagneticUnit::parse(unitArg.getValue());
    } catch (const std::invalid_argument& e) {
        return usage(std::string("--unit: ") + e.what());
    }
    const auto& args = positional.getValue();
    if (args.size() != (aalto ? 3u : 2u)) {
        return usage(aalto ? "expected DIR, TRIAL and OUT" : "expected FILE and OUT");
    }
    const auto model = drift.model();
    if (!(model.sp2 >= 0) || !(model.sh2 >= 0) || !(model.rate >= 0)) {
        return usage("--sp2, --sh2 and --odometry-rate must be >= 0");
    }
    // (An Aalto trial is a folder; a Kok walk a file the output must not overwrite.)
    io::refuseOutputOverInput(args.back(), {args[0]});
    io::refuseOutputOverInput(io::rawlogStem(args.back()) + ".gt.tum", {args[0]});
    MagneticRecording recording;
    if (aalto) {
        int trial = 0;
        try {
            std::size_t used = 0;
            trial = std::stoi(args[1], &used);
            if (used != args[1].size() || trial < 1) throw std::invalid_argument(args[1]);
        } catch (const std::exception&) {
            return usage("TRIAL '" + args[1] + "' is not a positive number");
        }
        recording = readAaltoTrial(args[0], trial, 0.05, unit);
    } else {
        recording = readKokWalk(args[0], unit);
    }
    printMagneticImport(writeMagneticRecording(recording, args.back(), model), out);
    return 0;
}

}  // namespace

int runImportApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    lodestone::registerAllClasses();
    const std::string usage =
        "lodestone-import: datasets into rawlogs\n"
        "usage: lodestone-import tum DIR OUT.rawlog [--intrinsics fr1] [--max-dt 0.02] [--depth-scale 5000]\n"
        "           [--depth-intrinsics fx,fy,cx,cy --depth-to-colour tx,ty,tz,qx,qy,qz,qw]\n"
        "       lodestone-import 7scenes DIR OUT.rawlog [--intrinsics fx,fy,cx,cy] [--depth-scale 1000]\n"
        "                              [--rate 30] [the same --depth-intrinsics / --depth-to-colour]\n"
        "       lodestone-import aalto DIR TRIAL OUT.rawlog [--seed 1] [--bias 0.005] [--sp2 "
        "1e-4]\n"
        "                              [--sh2 1e-4] [--odometry-rate 10] [--unit uT]\n"
        "       lodestone-import kok FILE.csv OUT.rawlog [same drift options] [--unit uT]\n"
        "         (--unit gauss|uT|T|normalized:<field strength in uT>: the field's unit in the\n"
        "          files; a field that is not Earth's in it is refused)\n"
        "exit codes: 0 ok, 1 bad input, 2 usage\n";
    if (argc < 2) {
        err << usage;
        return 2;
    }
    const std::string command = argv[1];
    if (command == "--help" || command == "-h") {
        out << usage;
        return 0;
    }
    std::vector<std::string> words = {"lodestone-import " + command};
    words.insert(words.end(), argv + 2, argv + argc);
    try {
        if (command == "tum") return importTum(words, out, err);
        if (command == "7scenes") return importSevenScenes(words, out, err);
        if (command == "aalto" || command == "kok") return importMagnetic(command, words, out, err);
    } catch (const std::exception& e) {
        err << "lodestone-import " << command << ": error: " << e.what() << "\n";
        return 1;
    }
    err << "lodestone-import: unknown dataset kind '" << command << "'\n" << usage;
    return 2;
}

}  // namespace lodestone::datasets
