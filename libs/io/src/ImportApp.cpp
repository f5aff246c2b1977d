#include <lodestone/config/CommandLine.h>
#include <lodestone/io/ImportApp.h>
#include <lodestone/io/TumRgbdImport.h>
#include <lodestone/obs/registerAllClasses.h>

#include <vector>

namespace lodestone::io {

namespace {
int importTum(const std::vector<std::string>& words, std::ostream& out, std::ostream& err) {
    TCLAP::CmdLine cmd("Convert a TUM RGB-D sequence folder into a rawlog (+ OUT.gt.tum)", ' ', "");
    TCLAP::UnlabeledMultiArg<std::string> positional(
        "DIR_OUT", "DIR (the sequence: rgb.txt, depth.txt, groundtruth.txt) then OUT.rawlog", true,
        "DIR OUT", cmd);
    TCLAP::ValueArg<std::string> intrinsics(
        "", "intrinsics", "fr1, fr2, fr3, default or fx,fy,cx,cy", false, "fr1", "K", cmd);
    TCLAP::ValueArg<double> maxDt("", "max-dt", "RGB-depth association tolerance [s]", false, 0.02,
                                  "S", cmd);
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
    o.maxTimeDifference = maxDt.getValue();
    const auto r = importTumRgbd(positional.getValue()[0], positional.getValue()[1], o);
    out << r.frames << " RGB-D frames -> " << r.rawlog << " (" << r.unmatchedRgb << " colour and "
        << r.unmatchedDepth << " depth images without a partner)\n";
    if (!r.groundTruth.empty()) {
        out << r.groundTruthPoses << " ground-truth poses -> " << r.groundTruth << "\n";
    }
    return 0;
}
}  // namespace

int runImportApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    lodestone::registerAllClasses();
    const std::string usage =
        "lodestone-import: datasets into rawlogs\n"
        "usage: lodestone-import tum DIR OUT.rawlog [--intrinsics fr1] [--max-dt 0.02]\n"
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
    } catch (const std::exception& e) {
        err << "lodestone-import " << command << ": error: " << e.what() << "\n";
        return 1;
    }
    err << "lodestone-import: unknown dataset kind '" << command << "'\n" << usage;
    return 2;
}

}  // namespace lodestone::io
