#include <lodestone/config/CommandLine.h>
#include <lodestone/obs/registerAllClasses.h>
#include <lodestone/sim/ScenarioPlot.h>
#include <lodestone/sim/ScenarioRecorder.h>
#include <SimApp.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <opencv2/imgcodecs.hpp>

namespace lodestone::sim {

int runSimApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    lodestone::registerAllClasses();
    TCLAP::CmdLine cmd(
        "Simulate an indoor run (RGB-D, magnetometers, wheel encoders, kidnaps) "
        "and write a rawlog with its ground truth",
        ' ', "");
    TCLAP::ValueArg<std::string> config("c", "config", "scenario INI (see config_ini/)", true, "",
                                        "INI", cmd);
    TCLAP::ValueArg<std::string> outArg("o", "out",
                                        "output rawlog (.rawlog or .rawlog.gz); OUT.gt.tum and "
                                        "OUT.events.txt are written beside it",
                                        false, "", "OUT", cmd);
    TCLAP::ValueArg<long> seed("s", "seed", "random seed (default: the INI's [scenario] seed)",
                               false, -1, "N", cmd);
    TCLAP::ValueArg<long> worldSeed("", "world-seed",
                                    "the building's own seed (walls, magnetic field), kept "
                                    "whatever --seed is: runs of other seeds in one building, "
                                    "e.g. to map once and localize later (default: the INI's "
                                    "[scenario] world_seed, else drawn from --seed)",
                                    false, -1, "N", cmd);
    TCLAP::ValueArg<std::string> plot("p", "plot", "write a top-view picture of the scenario",
                                      false, "", "PNG", cmd);
    TCLAP::ValueArg<std::string> camera("", "camera",
                                        "override the camera: WIDTHxHEIGHT@RATE (e.g. 320x240@15; "
                                        "sides 16..4096 px, rate up to 1000 Hz)",
                                        false, "", "WxH@HZ", cmd);
    TCLAP::ValueArg<std::string> imageFormat(
        "", "image-format",
        "colour files beside the rawlog: png (lossless, the default), jpg or jpg:QUALITY (1-100, "
        "default 90); depth stays in the rawlog (write OUT.rawlog.gz to compress it losslessly)",
        false, "", "FORMAT", cmd);
    TCLAP::SwitchArg embedded("", "embedded-images",
                              "keep colour images inside the rawlog (default: the INI's "
                              "external_images, beside it)",
                              cmd);
    TCLAP::SwitchArg cameraOnly("", "camera-only",
                                "record the RGB-D camera alone (no encoders, wheel drop or "
                                "magnetometers): a camera-only recording, for rgbd_only.ini",
                                cmd);
    TCLAP::SwitchArg handheld("", "handheld",
                              "the camera carried by hand along the path, alone (6-DoF, shaking: "
                              "a handheld RGB-D sequence; implies --camera-only)",
                              cmd);
    TCLAP::SwitchArg gyro("", "gyro",
                          "record a gyro too (CObservationIMU, label IMU, 100 Hz, MEMS noise and "
                          "bias; the INI's [gyro] section when it has one): on the robot, or "
                          "with --handheld rigid with the camera",
                          cmd);
    const auto outcome = config::parseCommandLine(cmd, std::vector<std::string>(argv, argv + argc));
    if (outcome.kind == config::ParseOutcome::Kind::UsageError) {
        err << "lodestone-sim: " << outcome.error << " (see lodestone-sim --help)\n";
        return 2;
    }
    if (outcome.kind == config::ParseOutcome::Kind::HelpShown) return 0;
    if (!outArg.isSet() && !plot.isSet()) {
        err << "lodestone-sim: nothing to do: give --out and/or --plot\n";
        return 2;
    }
    try {
        Scenario scenario = Scenario::load(config.getValue());
        if (camera.isSet() && !scenario.camera.override(camera.getValue())) {
            err << "lodestone-sim: --camera: expected WIDTHxHEIGHT@RATE (sides 16..4096 px, rate 0..1000 Hz), got '"
                << camera.getValue() << "'\n";
            return 2;
        }
        if (imageFormat.isSet() && !scenario.camera.setImageFormat(imageFormat.getValue())) {
            err << "lodestone-sim: --image-format: expected png, jpg or jpg:QUALITY (1-100), got '"
                << imageFormat.getValue() << "'\n";
            return 2;
        }
        if (embedded.getValue()) scenario.camera.externalImages = false;
        if (worldSeed.isSet()) {
            if (worldSeed.getValue() < 0) {
                err << "lodestone-sim: --world-seed must be >= 0\n";
                return 2;
            }
            scenario.worldSeed = static_cast<std::uint64_t>(worldSeed.getValue());
        }
        scenario.cameraOnly = cameraOnly.getValue() || handheld.getValue();
        if (handheld.getValue()) scenario.handheld = HandheldSpec{};
        if (gyro.getValue() && !scenario.gyro) scenario.gyro = GyroSpec{};
        const std::uint64_t s =
            seed.getValue() >= 0 ? static_cast<std::uint64_t>(seed.getValue()) : scenario.seed;
        SimulatorSource source(scenario, s);
        out << "scenario '" << scenario.name << "', seed " << s << ": " << std::fixed
            << std::setprecision(1) << source.duration() << " s, " << source.kidnapEvents().size()
            << " kidnap(s)\n";
        if (plot.isSet()) {
            if (!cv::imwrite(plot.getValue(), plotScenario(source))) {
                throw std::runtime_error(plot.getValue() + ": cannot write picture");
            }
            out << "picture -> " << plot.getValue() << "\n";
        }
        if (outArg.isSet()) {
            const auto wall0 = std::chrono::steady_clock::now();
            // Progress only for a person watching a terminal, not for logs and pipes.
            const bool terminal = &out == &std::cout && ::isatty(STDOUT_FILENO);
            const auto r = recordScenario(source, outArg.getValue(), [&](double f) {
                if (terminal)
                    out << "\r  " << std::setw(5) << std::setprecision(1) << 100 * f << " %"
                        << std::flush;
            });
            const double secs =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
            out << "\r" << r.observations << " observations (" << r.frames << " RGB-D frames), "
                << std::setprecision(1) << r.duration << " s simulated in " << secs << " s\n"
                << "  rawlog       " << r.rawlog << "\n"
                << "  ground truth " << r.groundTruth << "\n"
                << "  events       " << r.events << "\n";
            if (!r.imagesDir.empty()) out << "  images       " << r.imagesDir << "\n";
        }
    } catch (const std::exception& e) {
        err << "lodestone-sim: error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}

}  // namespace lodestone::sim
