#include <lodestone/config/CommandLine.h>
#include <lodestone/eval/ClosureEval.h>
#include <lodestone/eval/ClosureFunnel.h>
#include <EvalApp.h>
#include <lodestone/eval/RelocationEval.h>
#include <lodestone/eval/SegmentEval.h>
#include <lodestone/eval/TrajectoryPlot.h>
#include <lodestone/outputs/ClosureTable.h>
#include <lodestone/outputs/RunFiles.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

namespace lodestone::eval {

namespace {

using outputs::pathIn;
using outputs::RunFile;

int runRelocationEval(const std::string& dir, std::string truthPath, std::string eventsPath,
                      double maxDt, std::ostream& out, std::ostream& err) {
    try {
        if (truthPath.empty()) truthPath = pathIn(dir, RunFile::GroundTruth);
        if (eventsPath.empty()) eventsPath = pathIn(dir, RunFile::Events);
        const auto reported = readReportedKidnaps(pathIn(dir, RunFile::Report));
        const auto trajectory = io::readTumTrajectory(pathIn(dir, RunFile::Trajectory));
        const std::string before = pathIn(dir, RunFile::MapAtFirstKidnap);
        std::vector<io::TumPose> mapBefore;
        if (std::ifstream(before).good()) mapBefore = io::readTumTrajectory(before);
        const auto truth = io::readTumTrajectory(truthPath);
        const auto events = io::readKidnapEvents(eventsPath);
        RelocationEvalOptions options;
        options.maxDt = maxDt;
        out << formatRelocationEvaluation(
            evaluateRelocations(reported, trajectory, mapBefore, truth, events, options));
    } catch (const std::exception& e) {
        err << "lodestone-eval: error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}

int runClosureEval(const std::string& dir, std::string truthPath, double maxDt, double radius,
                   std::ostream& out, std::ostream& err) {
    try {
        if (truthPath.empty()) truthPath = pathIn(dir, RunFile::GroundTruth);
        const auto closures = outputs::readClosureTable(pathIn(dir, RunFile::Closures));
        const auto trajectory = io::readTumTrajectory(pathIn(dir, RunFile::Trajectory));
        const auto truth = io::readTumTrajectory(truthPath);
        ClosureEvalOptions options;
        options.maxDt = maxDt;
        options.radius = radius;
        const auto qualities = evaluateClosures(closures, trajectory, truth, options);
        out << formatClosureQuality(qualities, options);
        // The closers' recall funnels, when the run reported them (it had ground truth).
        const std::string report = pathIn(dir, RunFile::Report);
        if (std::ifstream(report)) {
            const auto funnels =
                readClosureFunnels(report, revisitPasses(trajectory, truth, options), qualities);
            if (!funnels.empty()) {
                out << "\nRecall funnel: every revisit pass a matcher missed, by the furthest "
                       "stage its true place reached in it\n\n"
                    << formatClosureFunnels(funnels);
            }
        }
    } catch (const std::exception& e) {
        err << "lodestone-eval: error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}

int runSegmentEval(const std::string& dir, std::string truthPath, double maxDt, std::ostream& out,
                   std::ostream& err) {
    try {
        if (truthPath.empty()) truthPath = pathIn(dir, RunFile::GroundTruth);
        const auto nodes = outputs::readNodeTable(pathIn(dir, RunFile::Nodes));
        const auto trajectory = io::readTumTrajectory(pathIn(dir, RunFile::Trajectory));
        const auto truth = io::readTumTrajectory(truthPath);
        auto evaluation = evaluateSegments(nodes, trajectory, truth, maxDt);
        if (evaluation.whole.pairs < 3) {
            throw std::runtime_error(truthPath + ": fewer than 3 poses of " +
                                     pathIn(dir, RunFile::Trajectory) + " match it in time");
        }
        const std::string report = pathIn(dir, RunFile::Report);
        if (std::ifstream(report)) evaluation.gapsReported = readVoGaps(report, evaluation.gapSeconds);
        out << formatSegmentEvaluation(evaluation);
    } catch (const std::exception& e) {
        err << "lodestone-eval: error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}

}  // namespace

int runEvalApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    TCLAP::CmdLine cmd(
        "Trajectory error of an estimate against ground truth (TUM RGB-D metrics).\n"
        "  lodestone-eval EST.tum GT.tum            ATE and RPE\n"
        "  lodestone-eval relocation SLAM_OUT_DIR   kidnaps of a lodestone-slam run, judged\n"
        "      (reads report.json, trajectory.tum, map_at_first_kidnap.tum, and the ground\n"
        "      truth and events that lodestone-slam --sim writes there, unless given)\n"
        "  lodestone-eval closures SLAM_OUT_DIR     each loop closer's proposals judged against\n"
        "      the truth: precision, recall of revisits, recall at 100 % precision (reads\n"
        "      closures.csv, trajectory.tum and ground_truth.tum unless --ground-truth)\n"
        "  lodestone-eval segments SLAM_OUT_DIR     the run's ATE whole and each segment's on\n"
        "      its own (pooled), beside its VO gaps (reads nodes.csv, trajectory.tum,\n"
        "      report.json and ground_truth.tum unless --ground-truth)",
        ' ', "");
    TCLAP::UnlabeledMultiArg<std::string> files(
        "EST_GT", "EST.tum then GT.tum (TUM format), or: relocation|closures|segments SLAM_OUT_DIR", true, "EST GT",
        cmd);
    TCLAP::ValueArg<std::string> truthArg("g", "ground-truth",
                                          "relocation, closures, segments: ground truth (default DIR/ground_truth.tum)",
                                          false, "", "TUM", cmd);
    TCLAP::ValueArg<std::string> eventsArg(
        "e", "events", "relocation: the simulator's kidnap events (default DIR/events.txt)", false,
        "", "TXT", cmd);
    TCLAP::ValueArg<std::string> plot("p", "plot", "write trajectories and error as a PNG", false,
                                      "", "PNG", cmd);
    TCLAP::ValueArg<double> maxDt("", "max-dt", "timestamp association tolerance [s]", false, 0.02,
                                  "S", cmd);
    TCLAP::ValueArg<double> radius("", "radius",
                                   "closures: a closure is right within this of the truth [m]",
                                   false, 0.5, "M", cmd);
    const auto outcome = config::parseCommandLine(cmd, std::vector<std::string>(argv, argv + argc));
    if (outcome.kind == config::ParseOutcome::Kind::HelpShown) return 0;
    if (outcome.kind == config::ParseOutcome::Kind::UsageError || files.getValue().size() != 2) {
        err << "lodestone-eval: "
            << (outcome.error.empty() ? "expected EST.tum and GT.tum" : outcome.error)
            << " (see lodestone-eval --help)\n";
        return 2;
    }
    const bool relocation = files.getValue().size() == 2 && files.getValue()[0] == "relocation";
    const bool closures = files.getValue().size() == 2 && files.getValue()[0] == "closures";
    const bool segments = files.getValue().size() == 2 && files.getValue()[0] == "segments";
    if ((!relocation && !closures && !segments && truthArg.isSet()) || (!relocation && eventsArg.isSet()) ||
        (!closures && radius.isSet())) {
        err << "lodestone-eval: --ground-truth belongs to 'relocation', 'closures' and "
               "'segments', --events to 'relocation', --radius to 'closures' (see lodestone-eval "
               "--help)\n";
        return 2;
    }
    if (closures) {
        if (!(radius.getValue() > 0)) {
            err << "lodestone-eval: --radius must be > 0\n";
            return 2;
        }
        return runClosureEval(files.getValue()[1], truthArg.getValue(), maxDt.getValue(),
                              radius.getValue(), out, err);
    }
    if (segments) {
        return runSegmentEval(files.getValue()[1], truthArg.getValue(), maxDt.getValue(), out, err);
    }
    if (relocation) {
        return runRelocationEval(files.getValue()[1], truthArg.getValue(), eventsArg.getValue(),
                                 maxDt.getValue(), out, err);
    }
    try {
        const auto est = io::readTumTrajectory(files.getValue()[0]);
        const auto gt = io::readTumTrajectory(files.getValue()[1]);
        const auto ate = absoluteTrajectoryError(est, gt, maxDt.getValue());
        if (ate.pairs < 3) {
            throw std::runtime_error("only " + std::to_string(ate.pairs) +
                                     " poses associate within " + std::to_string(maxDt.getValue()) +
                                     " s: are the timestamps of the same clock?");
        }
        const auto perSecond =
            relativePoseError(est, gt, RpeInterval::Seconds, 1.0, maxDt.getValue());
        const auto perMetre =
            relativePoseError(est, gt, RpeInterval::Metres, 1.0, maxDt.getValue());
        char line[200];
        std::snprintf(line, sizeof(line),
                      "associated poses     %zu of %zu (estimate) / %zu (truth)\n", ate.pairs,
                      est.size(), gt.size());
        out << line;
        std::snprintf(line, sizeof(line), "ATE  RMSE %.4f m   mean %.4f   median %.4f   max %.4f\n",
                      ate.rmse, ate.mean, ate.median, ate.max);
        out << line;
        std::snprintf(line, sizeof(line), "RPE  per second: %.4f m, %.3f deg   (%zu pairs)\n",
                      perSecond.translationRmse, perSecond.rotationRmse * 180 / M_PI,
                      perSecond.pairs);
        out << line;
        std::snprintf(line, sizeof(line), "RPE  per metre:  %.2f %%, %.3f deg   (%zu pairs)\n",
                      100 * perMetre.translationRmse, perMetre.rotationRmse * 180 / M_PI,
                      perMetre.pairs);
        out << line;
        if (plot.isSet()) {
            if (!cv::imwrite(plot.getValue(), plotTrajectories(est, gt, ate))) {
                throw std::runtime_error(plot.getValue() + ": cannot write picture");
            }
            out << "plot -> " << plot.getValue() << "\n";
        }
    } catch (const std::exception& e) {
        err << "lodestone-eval: error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}

}  // namespace lodestone::eval
