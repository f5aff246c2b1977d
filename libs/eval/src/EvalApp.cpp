#include <lodestone/config/CommandLine.h>
#include <lodestone/eval/EvalApp.h>
#include <lodestone/eval/TrajectoryPlot.h>

#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>

namespace lodestone::eval {

int runEvalApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    TCLAP::CmdLine cmd("Trajectory error of an estimate against ground truth (TUM RGB-D metrics)",
                       ' ', "");
    TCLAP::UnlabeledMultiArg<std::string> files("EST_GT", "EST.tum then GT.tum (TUM format)", true,
                                                "EST GT", cmd);
    TCLAP::ValueArg<std::string> plot("p", "plot", "write trajectories and error as a PNG", false,
                                      "", "PNG", cmd);
    TCLAP::ValueArg<double> maxDt("", "max-dt", "timestamp association tolerance [s]", false, 0.02,
                                  "S", cmd);
    const auto outcome = config::parseCommandLine(cmd, std::vector<std::string>(argv, argv + argc));
    if (outcome.kind == config::ParseOutcome::Kind::HelpShown) return 0;
    if (outcome.kind == config::ParseOutcome::Kind::UsageError || files.getValue().size() != 2) {
        err << "lodestone-eval: "
            << (outcome.error.empty() ? "expected EST.tum and GT.tum" : outcome.error)
            << " (see lodestone-eval --help)\n";
        return 2;
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
