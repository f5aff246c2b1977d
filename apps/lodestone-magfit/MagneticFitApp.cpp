#include <lodestone/config/CommandLine.h>
#include <lodestone/graphslam/erd/magnetic/MagneticGpERD.h>
#include <lodestone/io/RawlogReadError.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/magnetic/DistanceResampler.h>
#include <lodestone/magnetic/FieldFeatures.h>
#include <lodestone/magnetic/HyperparameterFit.h>
#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/obs/MagneticUnit.h>
#include <lodestone/obs/registerAllClasses.h>
#include <MagneticFitApp.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/system/datetime.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <ostream>

namespace lodestone::slamapp {

namespace {

struct PathSample {
    double t, travel, heading;
};
struct Reading {
    double t;
    Eigen::Vector3d robotField;
};

/** The odometry's travel and heading at time t (linear between samples, held outside). */
PathSample pathAt(const std::vector<PathSample>& path, double t) {
    const auto it = std::lower_bound(path.begin(), path.end(), t,
                                     [](const PathSample& p, double v) { return p.t < v; });
    if (it == path.begin()) return path.front();
    if (it == path.end()) return path.back();
    const auto& a = *(it - 1);
    const auto& b = *it;
    const double f = b.t > a.t ? (t - a.t) / (b.t - a.t) : 1.0;
    return {t, a.travel + f * (b.travel - a.travel), a.heading + f * (b.heading - a.heading)};
}

/** What a recording gives the fit: the odometry path and one sensor's readings. */
struct Recording {
    std::vector<PathSample> odometry;
    std::vector<Reading> readings;
    std::size_t dropped{0}, otherSensors{0};
};

/** Reads the rawlog's odometry poses and magnetometer readings (the first sensor seen, unless
 * `p.sensorLabel` names one: then it is set). Throws on a read error (file, entry, offset). */
Recording readRecording(const std::string& path, graphslam::MagneticGpERD::Params& p,
                        const obs::MagneticUnit& unit) {
    Recording r;
    std::optional<mrpt::poses::CPose2D> lastPose;
    io::RawlogSource source(path);
    while (auto obs = source.next()) {
        const double t = mrpt::Clock::toDouble(obs->timestamp);
        if (auto o = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs)) {
            auto& odometry = r.odometry;
            const double travel =
                odometry.empty()
                    ? 0.0
                    : odometry.back().travel +
                          std::hypot(o->odometry.x() - lastPose->x(), o->odometry.y() - lastPose->y());
            double heading = o->odometry.phi();
            if (!odometry.empty()) {  // unwrapped, so that interpolation is meaningful
                heading = odometry.back().heading +
                          mrpt::math::wrapToPi(heading - odometry.back().heading);
            }
            odometry.push_back({t, travel, heading});
            lastPose = o->odometry;
        } else if (auto m = std::dynamic_pointer_cast<obs::CObservationMagnetometer>(obs)) {
            if (p.sensorLabel.empty()) p.sensorLabel = m->sensorLabel;
            if (m->sensorLabel != p.sensorLabel) {
                ++r.otherSensors;
                continue;
            }
            const Eigen::Vector3d inSensor =
                unit.microteslaPerUnit * Eigen::Vector3d(m->field.x, m->field.y, m->field.z);
            if (!magnetic::usableReading(inSensor, p.saturation)) {
                ++r.dropped;
                continue;
            }
            r.readings.push_back({t, m->sensorPose.getRotationMatrix().asEigen() * inSensor});
        }
    }
    return r;
}

/** The readings resampled by distance along the odometry and cut into stretches of
 * `perStretch` points (a last one of at least half that, and 8, kept). */
std::vector<magnetic::FieldStretch> cutStretches(const Recording& r,
                                                 const graphslam::MagneticGpERD::Params& p,
                                                 std::size_t perStretch) {
    std::vector<magnetic::FieldStretch> stretches;
    magnetic::DistanceResampler resampler(p.track.step);
    std::vector<double> xs;
    std::vector<Eigen::VectorXd> ys;
    const auto flush = [&] {
        if (xs.size() >= std::max<std::size_t>(8, perStretch / 2)) {
            magnetic::FieldStretch s;
            s.travel = xs;
            s.readings.resize(static_cast<Eigen::Index>(xs.size()), ys.front().size());
            for (std::size_t i = 0; i < ys.size(); ++i)
                s.readings.row(static_cast<Eigen::Index>(i)) = ys[i].transpose();
            stretches.push_back(std::move(s));
        }
        xs.clear();
        ys.clear();
    };
    for (const auto& reading : r.readings) {
        const auto at = pathAt(r.odometry, reading.t);
        for (const auto& s :
             resampler.add(at.travel, magnetic::fieldFeature(reading.robotField, at.heading, p.mode))) {
            xs.push_back(s.s);
            ys.push_back(s.value);
            if (xs.size() == perStretch) flush();
        }
    }
    flush();
    return stretches;
}

/** The command line's values, checked; `usage` says what is wrong (exit 2). */
struct FitArgs {
    std::string rawlog;
    std::optional<std::string> config, sensor, mode;  ///< as given, when given
    obs::MagneticUnit unit;                            ///< the rawlog's magnetometers
    double stretch{10.0}, step{0.0};                  ///< step 0: the INI's
    bool helpShown{false};
    std::string usage;
};

FitArgs parseArgs(int argc, const char* const* argv) {
    TCLAP::CmdLine cmd(
        "Fit MagneticGpERD's along-the-path GP hyperparameters to a recording (maximum marginal "
        "likelihood); prints the [MagneticGpERD] lines",
        ' ', "");
    TCLAP::UnlabeledValueArg<std::string> rawlogArg("rawlog", "input rawlog", true, "", "RAWLOG",
                                                    cmd);
    TCLAP::ValueArg<std::string> configArg(
        "c", "config", "start values, field mode, sensor and step from this INI's [MagneticGpERD]",
        false, "", "INI", cmd);
    TCLAP::ValueArg<std::string> sensorArg("", "sensor", "only this magnetometer label", false, "",
                                           "LABEL", cmd);
    TCLAP::ValueArg<std::string> modeArg("", "mode", "field feature: invariant | vector", false, "",
                                         "MODE", cmd);
    TCLAP::ValueArg<double> stretchArg("", "stretch", "length of each fitted stretch [m]", false,
                                       10.0, "M", cmd);
    TCLAP::ValueArg<double> stepArg("", "step", "resampling interval [m]", false, 0.0, "M", cmd);
    TCLAP::ValueArg<std::string> unitArg(
        "", "magnetic-unit",
        std::string("the unit the rawlog's magnetometer numbers are in, if not microtesla: ") +
            obs::kMagneticUnitChoices,
        false, "uT", "UNIT", cmd);
    FitArgs a;
    const auto outcome = config::parseCommandLine(cmd, std::vector<std::string>(argv, argv + argc));
    a.helpShown = outcome.kind == config::ParseOutcome::Kind::HelpShown;
    a.usage = outcome.error;
    a.rawlog = rawlogArg.getValue();
    if (configArg.isSet()) a.config = configArg.getValue();
    if (sensorArg.isSet()) a.sensor = sensorArg.getValue();
    if (modeArg.isSet()) a.mode = modeArg.getValue();
    a.stretch = stretchArg.getValue();
    const bool stepSet = stepArg.isSet();
    a.step = stepSet ? stepArg.getValue() : 0.0;
    if (a.usage.empty() && !(a.stretch > 0)) a.usage = "--stretch must be > 0";
    if (a.usage.empty()) {
        try {
            a.unit = obs::MagneticUnit::parse(unitArg.getValue());
        } catch (const std::invalid_argument& e) {
            a.usage = std::string("--magnetic-unit: ") + e.what();
        }
    }
    if (a.usage.empty() && stepSet && !(a.step > 0)) a.usage = "--step must be > 0";
    // A stretch's GP costs the cube of its points: beyond this, a typo (1e-9) not a fit.
    constexpr double kMaxPointsPerStretch = 4000;
    if (a.usage.empty() && stepSet && a.stretch / a.step > kMaxPointsPerStretch) {
        a.usage = "--step " + std::to_string(a.step) + " gives " +
                  std::to_string(a.stretch / a.step) + " points per --stretch; at most " +
                  std::to_string(int(kMaxPointsPerStretch));
    }
    return a;
}

}  // namespace

int runMagneticFitApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    const FitArgs args = parseArgs(argc, argv);
    if (args.helpShown) return 0;
    if (!args.usage.empty()) {
        err << "lodestone-magfit: " << args.usage << " (see lodestone-magfit --help)\n";
        return 2;
    }
    lodestone::registerAllClasses();
    const std::string& path = args.rawlog;
    graphslam::MagneticGpERD::Params p;
    try {
        if (args.config) {
            if (!std::filesystem::exists(*args.config))
                throw std::runtime_error("cannot open configuration file '" + *args.config + "'");
            graphslam::MagneticGpERD erd;  // reads [MagneticGpERD] strictly
            erd.configure(mrpt::config::CConfigFile(*args.config));
            p = erd.params();
        }
        if (args.mode) p.mode = magnetic::parseFieldMode(*args.mode);
    } catch (const std::exception& e) {
        err << "lodestone-magfit: " << e.what() << "\n";
        return 1;
    }
    if (args.sensor) p.sensorLabel = *args.sensor;
    if (args.step > 0) p.track.step = args.step;
    if (!std::filesystem::is_regular_file(path)) {
        err << "lodestone-magfit: cannot open rawlog '" << path << "'"
            << (std::filesystem::is_directory(path) ? ": a directory" : "") << "\n";
        return 1;
    }
    Recording recording;
    try {
        recording = readRecording(path, p, args.unit);
    } catch (const std::exception& e) {  // a read error names the file, entry and offset
        err << "lodestone-magfit: " << e.what() << "\n";
        return 1;
    }
    if (recording.readings.empty()) {
        err << "lodestone-magfit: " << path << ": no usable CObservationMagnetometer readings"
            << (p.sensorLabel.empty() ? "" : " from sensor '" + p.sensorLabel + "'") << "\n";
        return 1;
    }
    std::vector<double> magnitudes;
    for (const auto& reading : recording.readings) magnitudes.push_back(reading.robotField.norm());
    if (const auto why = obs::implausibleFieldMagnitude(std::move(magnitudes))) {
        err << "lodestone-magfit: " << path << ": its magnetometer, read as " << args.unit.name
            << ": " << *why << "; give the unit it is in with --magnetic-unit "
            << obs::kMagneticUnitChoices << "\n";
        return 1;
    }
    const auto& odometry = recording.odometry;
    if (odometry.size() < 2) {
        err << "lodestone-magfit: " << path
            << ": needs CObservationOdometry poses for the distance travelled\n";
        return 1;
    }
    const auto stretches = cutStretches(
        recording, p, static_cast<std::size_t>(std::lround(args.stretch / p.track.step)));
    if (stretches.empty()) {
        err << "lodestone-magfit: " << path << ": the odometry travelled too little ("
            << odometry.back().travel << " m) for one stretch of " << args.stretch << " m\n";
        return 1;
    }
    double startLog = 0;
    for (const auto& s : stretches)
        startLog += magnetic::GaussianProcess1D::logMarginal(s.travel, s.readings, p.gp);
    const auto fit = magnetic::fitHyperparameters(stretches, p.gp);
    const auto& h = fit.hyperparameters;
    out << "; lodestone-magfit " << path << ": sensor '" << p.sensorLabel << "', field_mode "
        << magnetic::toString(p.mode) << ", " << recording.readings.size() << " readings ("
        << recording.dropped << " unusable dropped, " << recording.otherSensors
        << " from other sensors), " << odometry.back().travel << " m of odometry, "
        << stretches.size() << " stretches of " << args.stretch << " m\n";
    out << "; log marginal likelihood " << startLog << " at the start values -> " << fit.logMarginal
        << " (" << fit.iterations << " iterations, " << (fit.converged ? "converged" : "not converged")
        << ")\n";
    out << "[MagneticGpERD]\n";
    out << "gp_sigma_f      = " << h.sigmaF << "\n";
    out << "gp_length_scale = " << h.lengthScale << "\n";
    out << "gp_sigma_n      = " << h.sigmaN << "\n";
    out << "gp_sigma_c      = " << h.sigmaC << "\n";
    return 0;
}

}  // namespace lodestone::slamapp
