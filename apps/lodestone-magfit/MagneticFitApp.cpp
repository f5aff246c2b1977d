#include <lodestone/config/CommandLine.h>
#include <lodestone/graphslam/erd/magnetic/MagneticGpERD.h>
#include <lodestone/io/RawlogReadError.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/magnetic/DistanceResampler.h>
#include <lodestone/magnetic/FieldFeatures.h>
#include <lodestone/magnetic/HyperparameterFit.h>
#include <lodestone/obs/CObservationMagnetometer.h>
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

}  // namespace

int runMagneticFitApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
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
    const auto outcome = config::parseCommandLine(cmd, std::vector<std::string>(argv, argv + argc));
    if (outcome.kind == config::ParseOutcome::Kind::HelpShown) return 0;
    std::string usage = outcome.error;
    if (usage.empty() && !(stretchArg.getValue() > 0)) usage = "--stretch must be > 0";
    if (usage.empty() && stepArg.isSet() && !(stepArg.getValue() > 0)) usage = "--step must be > 0";
    // A stretch's GP costs the cube of its points: beyond this, a typo (1e-9) not a fit.
    constexpr double kMaxPointsPerStretch = 4000;
    if (usage.empty() && stepArg.isSet() &&
        stretchArg.getValue() / stepArg.getValue() > kMaxPointsPerStretch) {
        usage = "--step " + std::to_string(stepArg.getValue()) + " gives " +
                std::to_string(stretchArg.getValue() / stepArg.getValue()) +
                " points per --stretch; at most " + std::to_string(int(kMaxPointsPerStretch));
    }
    if (!usage.empty()) {
        err << "lodestone-magfit: " << usage << " (see lodestone-magfit --help)\n";
        return 2;
    }
    lodestone::registerAllClasses();
    const std::string path = rawlogArg.getValue();
    graphslam::MagneticGpERD::Params p;
    try {
        if (configArg.isSet()) {
            if (!std::filesystem::exists(configArg.getValue()))
                throw std::runtime_error("cannot open configuration file '" + configArg.getValue() +
                                         "'");
            graphslam::MagneticGpERD erd;  // reads [MagneticGpERD] strictly
            erd.configure(mrpt::config::CConfigFile(configArg.getValue()));
            p = erd.params();
        }
        if (modeArg.isSet()) p.mode = magnetic::parseFieldMode(modeArg.getValue());
    } catch (const std::exception& e) {
        err << "lodestone-magfit: " << e.what() << "\n";
        return 1;
    }
    if (sensorArg.isSet()) p.sensorLabel = sensorArg.getValue();
    if (stepArg.isSet()) p.track.step = stepArg.getValue();
    if (!std::filesystem::is_regular_file(path)) {
        err << "lodestone-magfit: cannot open rawlog '" << path << "'"
            << (std::filesystem::is_directory(path) ? ": a directory" : "") << "\n";
        return 1;
    }

    // --- Read: odometry path and magnetometer readings ------------------------------------------
    std::vector<PathSample> odometry;
    std::vector<Reading> readings;
    std::size_t dropped = 0, otherSensors = 0;
    std::optional<mrpt::poses::CPose2D> lastPose;
    try {
        io::RawlogSource source(path);
        while (auto obs = source.next()) {
            const double t = mrpt::Clock::toDouble(obs->timestamp);
            if (auto o = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs)) {
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
                    ++otherSensors;
                    continue;
                }
                const Eigen::Vector3d inSensor(m->field.x, m->field.y, m->field.z);
                if (!magnetic::usableReading(inSensor, p.saturation)) {
                    ++dropped;
                    continue;
                }
                readings.push_back(
                    {t, m->sensorPose.getRotationMatrix().asEigen() * inSensor});
            }
        }
    } catch (const std::exception& e) {  // a read error names the file, entry and offset
        err << "lodestone-magfit: " << e.what() << "\n";
        return 1;
    }
    if (readings.empty()) {
        err << "lodestone-magfit: " << path << ": no usable CObservationMagnetometer readings"
            << (p.sensorLabel.empty() ? "" : " from sensor '" + p.sensorLabel + "'") << "\n";
        return 1;
    }
    if (odometry.size() < 2) {
        err << "lodestone-magfit: " << path
            << ": needs CObservationOdometry poses for the distance travelled\n";
        return 1;
    }

    // --- Resample by distance, cut into stretches -----------------------------------------------
    std::vector<magnetic::FieldStretch> stretches;
    magnetic::DistanceResampler resampler(p.track.step);
    std::vector<double> xs;
    std::vector<Eigen::VectorXd> ys;
    const auto perStretch = static_cast<std::size_t>(std::lround(stretchArg.getValue() / p.track.step));
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
    for (const auto& r : readings) {
        const auto at = pathAt(odometry, r.t);
        for (const auto& s :
             resampler.add(at.travel, magnetic::fieldFeature(r.robotField, at.heading, p.mode))) {
            xs.push_back(s.s);
            ys.push_back(s.value);
            if (xs.size() == perStretch) flush();
        }
    }
    flush();
    if (stretches.empty()) {
        err << "lodestone-magfit: " << path << ": the odometry travelled too little ("
            << odometry.back().travel << " m) for one stretch of " << stretchArg.getValue()
            << " m\n";
        return 1;
    }
    const auto startLog = [&] {
        double v = 0;
        for (const auto& s : stretches)
            v += magnetic::GaussianProcess1D::logMarginal(s.travel, s.readings, p.gp);
        return v;
    }();
    const auto fit = magnetic::fitHyperparameters(stretches, p.gp);
    const auto& h = fit.hyperparameters;
    out << "; lodestone-magfit " << path << ": sensor '" << p.sensorLabel << "', field_mode "
        << magnetic::toString(p.mode) << ", " << readings.size() << " readings (" << dropped
        << " unusable dropped, " << otherSensors << " from other sensors), "
        << odometry.back().travel << " m of odometry, " << stretches.size() << " stretches of "
        << stretchArg.getValue() << " m\n";
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
