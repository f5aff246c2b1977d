#include <lodestone/io/CsvTable.h>
#include <lodestone/datasets/MagneticRecording.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace lodestone::datasets {

namespace {

// Continuous angle: `a` moved by whole turns to lie within pi of `previous`.
double unwrapNear(double a, double previous) {
    return previous + std::remainder(a - previous, 2 * M_PI);
}

/** A recording needs samples, and numbers: `inf` or `nan` in a cell would travel on into the
 * rawlog and the ground truth. */
void requireFiniteSamples(const io::CsvTable& t, std::size_t columns) {
    if (t.rows() < 2) {
        throw std::runtime_error(t.path() + ": " + std::to_string(t.rows()) +
                                 " data rows; a recording needs at least 2");
    }
    for (std::size_t r = 0; r < t.rows(); ++r) {
        for (std::size_t c = 0; c < columns; ++c) {
            if (!std::isfinite(t.at(r, c))) {
                throw std::runtime_error(t.path() + ": line " + std::to_string(t.lineOf(r)) +
                                         ", column " + std::to_string(c + 1) +
                                         ": not a finite number");
            }
        }
    }
}

void requireTimeOrder(const io::CsvTable& times, std::size_t column) {
    for (std::size_t r = 1; r < times.rows(); ++r) {
        if (!(times.at(r, column) > times.at(r - 1, column))) {
            throw std::runtime_error(times.path() + ": line " + std::to_string(times.lineOf(r)) +
                                     ": time does not increase");
        }
    }
}

// Heading from the direction of travel: the chord between the points `baseline` metres of
// path before and after each sample; where the robot has not moved that far on both sides the
// previous heading is held (the first valid one is used backwards).
std::vector<double> headingFromTravel(const std::vector<Eigen::Vector2d>& p, double baseline) {
    const std::size_t n = p.size();
    std::vector<double> s(n, 0.0);  // path length
    for (std::size_t i = 1; i < n; ++i) s[i] = s[i - 1] + (p[i] - p[i - 1]).norm();
    std::vector<double> heading(n, std::nan(""));
    std::size_t back = 0, ahead = 0;
    for (std::size_t i = 0; i < n; ++i) {
        while (back + 1 < i && s[i] - s[back + 1] >= baseline) ++back;
        if (ahead < i) ahead = i;
        while (ahead + 1 < n && s[ahead] - s[i] < baseline) ++ahead;
        if (s[i] - s[back] < baseline || s[ahead] - s[i] < baseline) continue;
        const Eigen::Vector2d d = p[ahead] - p[back];
        heading[i] = std::atan2(d.y(), d.x());
    }
    std::size_t first = 0;
    while (first < n && std::isnan(heading[first])) ++first;
    if (first == n) return std::vector<double>(n, 0.0);  // never moved
    for (std::size_t i = 0; i < first; ++i) heading[i] = heading[first];
    for (std::size_t i = first + 1; i < n; ++i) {
        heading[i] =
            std::isnan(heading[i]) ? heading[i - 1] : unwrapNear(heading[i], heading[i - 1]);
    }
    return heading;
}

}  // namespace

double MagneticRecording::pathLength() const {
    double length = 0;
    for (std::size_t i = 1; i < samples.size(); ++i) {
        length += std::hypot(samples[i].x - samples[i - 1].x, samples[i].y - samples[i - 1].y);
    }
    return length;
}

MagneticRecording readAaltoTrial(const std::string& dir, int trial, double headingBaseline,
                                 const obs::MagneticUnit& unit) {
    const std::string stem = dir + "/" + std::to_string(trial) + "-";
    const auto times = io::CsvTable::read(stem + "time.csv", 1);
    requireFiniteSamples(times, 1);
    requireTimeOrder(times, 0);
    const auto loc = io::CsvTable::read(stem + "loc.csv", 2);
    const auto mag = io::CsvTable::read(stem + "mag.csv", 3);
    for (const io::CsvTable* t : {&loc, &mag}) {
        if (t->rows() != times.rows()) {
            throw std::runtime_error(t->path() + ": " + std::to_string(t->rows()) + " rows, but " +
                                     times.path() + " has " + std::to_string(times.rows()));
        }
    }
    requireFiniteSamples(loc, 2);
    requireFiniteSamples(mag, 3);
    std::vector<Eigen::Vector2d> p(loc.rows());
    for (std::size_t r = 0; r < loc.rows(); ++r) {
        p[r] = {loc.at(r, 0), loc.at(r, 1)};
        if (!p[r].allFinite()) {
            throw std::runtime_error(loc.path() + ": line " + std::to_string(loc.lineOf(r)) +
                                     ": position is not finite");
        }
    }
    const auto heading = headingFromTravel(p, headingBaseline);
    MagneticRecording rec;
    rec.name = "aalto trial " + std::to_string(trial);
    rec.calibrated = true;
    rec.samples.resize(times.rows());
    for (std::size_t r = 0; r < times.rows(); ++r) {
        auto& s = rec.samples[r];
        s.t = times.at(r, 0);
        s.x = p[r].x();
        s.y = p[r].y();
        s.heading = heading[r];
        // World frame -> robot frame: rotate by -heading about the vertical.
        const double c = std::cos(heading[r]), sn = std::sin(heading[r]);
        const double k = unit.microteslaPerUnit;
        const double wx = k * mag.at(r, 0), wy = k * mag.at(r, 1);
        s.field = {c * wx + sn * wy, -sn * wx + c * wy, k * mag.at(r, 2)};
    }
    requirePlausibleField(rec, mag.path());
    return rec;
}

MagneticRecording readKokWalk(const std::string& csvPath, const obs::MagneticUnit& unit) {
    const auto t = io::CsvTable::read(csvPath, 12, 1);
    requireFiniteSamples(t, 12);
    requireTimeOrder(t, 0);
    MagneticRecording rec;
    rec.name = "kok " + csvPath.substr(csvPath.find_last_of('/') + 1);
    rec.samples.resize(t.rows());
    // The magnetometer's axes are the device's turned by +90 deg about its z axis (found by
    // the world-frame field being most nearly constant over both walks; Kok & Solin apply the
    // same quarter turn).
    const Eigen::Matrix3d magOnDevice =
        Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    double previousHeading = 0;
    for (std::size_t r = 0; r < t.rows(); ++r) {
        Eigen::Quaterniond q(t.at(r, 5), t.at(r, 6), t.at(r, 7), t.at(r, 8));
        if (!(std::abs(q.norm() - 1) < 0.01)) {
            throw std::runtime_error(csvPath + ": line " + std::to_string(t.lineOf(r)) +
                                     ": orientation is not a unit quaternion");
        }
        const Eigen::Matrix3d R = q.normalized().toRotationMatrix();  // device -> world
        const double yaw = std::atan2(R(1, 0), R(0, 0));
        auto& s = rec.samples[r];
        s.t = t.at(r, 0);
        s.x = t.at(r, 2);
        s.y = t.at(r, 3);
        s.heading = r == 0 ? yaw : unwrapNear(yaw, previousHeading);
        previousHeading = s.heading;
        // Levelled: the world-frame field turned back by the heading only.
        const Eigen::Vector3d m =
            unit.microteslaPerUnit * Eigen::Vector3d(t.at(r, 9), t.at(r, 10), t.at(r, 11));
        const Eigen::Vector3d level =
            Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()) * (R * (magOnDevice * m));
        s.field = {level.x(), level.y(), level.z()};
    }
    requirePlausibleField(rec, csvPath);
    return rec;
}

void writeKokWalk(const MagneticRecording& recording, const std::string& csvPath,
                  const obs::MagneticUnit& unit) {
    std::ofstream out(csvPath);
    if (!out) throw std::runtime_error(csvPath + ": cannot open for writing");
    out << "t,tm,px,py,pz,q0,q1,q2,q3,mx,my,mz\n";
    // readKokWalk's quarter turn of the magnetometer on the device, undone.
    const Eigen::Matrix3d deviceOnMag =
        Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    char line[512];
    for (const auto& s : recording.samples) {
        const Eigen::Vector3d m = deviceOnMag * Eigen::Vector3d(s.field.x, s.field.y, s.field.z) /
                                  unit.microteslaPerUnit;
        std::snprintf(line, sizeof line,
                      "%.17g,%.17g,%.17g,%.17g,0,%.17g,0,0,%.17g,%.17g,%.17g,%.17g\n", s.t, s.t,
                      s.x, s.y, std::cos(0.5 * s.heading), std::sin(0.5 * s.heading), m.x(), m.y(),
                      m.z());
        out << line;
    }
    out.close();
    if (!out) throw std::runtime_error(csvPath + ": write failed");
}

void requirePlausibleField(const MagneticRecording& recording, const std::string& source) {
    std::vector<double> magnitudes;
    magnitudes.reserve(recording.samples.size());
    for (const auto& s : recording.samples) magnitudes.push_back(s.field.norm());
    if (const auto why = obs::implausibleFieldMagnitude(std::move(magnitudes))) {
        throw std::runtime_error(source + ": " + *why + "; give the readings' unit with --unit " +
                                 obs::kMagneticUnitChoices);
    }
}

}  // namespace lodestone::datasets
