#include "magnetic_recordings.h"

#include <lodestone/datasets/MagneticRecordingImport.h>

#include <Eigen/Core>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>

using namespace lodestone;

namespace {

/** The earth's field plus Gaussian anomalies (+-6 uT per component, 0.3-0.6 m wide), two per
 * metre of the given segments, up to 1 m beside them. */
class SyntheticField {
  public:
    SyntheticField(const std::vector<Eigen::Vector2d>& polyline, unsigned seed) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(0, 1), a(-6, 6), lateral(-1, 1), width(0.3, 0.6);
        for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
            const Eigen::Vector2d d = polyline[i + 1] - polyline[i];
            const double len = d.norm();
            const Eigen::Vector2d across(-d.y() / len, d.x() / len);
            for (int k = 0; k < static_cast<int>(2 * len); ++k) {
                const double f = u(rng), off = lateral(rng);
                const Eigen::Vector2d c = polyline[i] + f * d + off * across;
                bumps_.push_back({c, {a(rng), a(rng), a(rng)}, width(rng)});
            }
        }
    }
    /** The field a walker at (p, heading) reads, in its levelled frame. */
    Eigen::Vector3d reading(const Eigen::Vector2d& p, double heading) const {
        Eigen::Vector3d b(15, 0, -45);
        for (const auto& bump : bumps_) {
            const double d2 = (p - bump.centre).squaredNorm();
            if (d2 > 9 * bump.width * bump.width) continue;
            b += bump.amplitude * std::exp(-0.5 * d2 / (bump.width * bump.width));
        }
        const double c = std::cos(heading), s = std::sin(heading);
        return {c * b.x() + s * b.y(), -s * b.x() + c * b.y(), b.z()};
    }

  private:
    struct Bump {
        Eigen::Vector2d centre;
        Eigen::Vector3d amplitude;
        double width;
    };
    std::vector<Bump> bumps_;
};

void addSample(datasets::MagneticRecording& rec, double t, const Eigen::Vector2d& p, double heading,
               const SyntheticField& field) {
    const Eigen::Vector3d b = field.reading(p, heading);
    rec.samples.push_back({t, p.x(), p.y(), heading, {b.x(), b.y(), b.z()}});
}

}  // namespace

datasets::MagneticRecording syntheticLongWalk(int laps) {
    const double w = 40, h = 20;
    const std::vector<Eigen::Vector2d> corners = {{0, 0}, {w, 0}, {w, h}, {0, h}, {0, 0}};
    const SyntheticField field(corners, 29);
    datasets::MagneticRecording rec;
    rec.name = "synthetic long walk";
    rec.calibrated = true;
    double t = 0, heading = 0;
    for (int lap = 0; lap < laps; ++lap) {
        const double inset = 0.3 * (lap % 2);  // every second lap passes beside the first
        for (int side = 0; side < 4; ++side) {
            const Eigen::Vector2d d = corners[side + 1] - corners[side];
            const double len = d.norm();
            const Eigen::Vector2d across(-d.y() / len, d.x() / len);
            heading += std::remainder(std::atan2(d.y(), d.x()) - heading, 2 * M_PI);
            for (double s = 0; s < len; s += 0.12, t += 0.1)
                addSample(rec, t, corners[side] + d * s / len + inset * across, heading, field);
        }
    }
    return rec;
}

datasets::MagneticRecording syntheticCorridorWalk() {
    const double length = 30;
    const SyntheticField field({{0, 0}, {length, 0}}, 31);
    std::mt19937 rng(37);
    std::uniform_real_distribution<double> offset(-0.15, 0.15);
    datasets::MagneticRecording rec;
    rec.name = "synthetic corridor";
    rec.calibrated = true;
    double t = 0, heading = 0;
    for (int pass = 0; pass < 6; ++pass) {
        const bool east = pass % 2 == 0;
        const double y = offset(rng);
        // Turn on the spot at the corridor's end: half a turn over 1 s.
        const double target = heading + (pass == 0 ? 0.0 : M_PI);
        for (int k = 1; pass > 0 && k <= 10; ++k, t += 0.1)
            addSample(rec, t, {east ? 0.0 : length, y}, heading + (target - heading) * k / 10,
                      field);
        heading = target;
        for (double s = 0; s < length; s += 0.12, t += 0.1)
            addSample(rec, t, {east ? s : length - s, y}, heading, field);
    }
    return rec;
}

std::vector<Recording> benchRecordings(const std::string& data) {
    std::vector<Recording> recs;
    if (std::filesystem::is_directory(data)) {
        for (int t = 1; t <= 9; ++t) {
            recs.push_back({"aalto " + std::to_string(t),
                            [=] { return datasets::readAaltoTrial(data + "/aalto/invensense", t); }});
        }
        for (const char* w : {"eight", "square"}) {
            recs.push_back({std::string("kok ") + w,
                            [=] { return datasets::readKokWalk(data + "/kok/" + w + ".csv"); }});
        }
    }
    recs.push_back({"synthetic longwalk", [] { return syntheticLongWalk(); }});
    recs.push_back({"synthetic corridor", [] { return syntheticCorridorWalk(); }});
    return recs;
}

datasets::MagneticImportResult importSeed(const datasets::MagneticRecording& recording, const std::string& path,
                                    int seed, double driftScale) {
    datasets::OdometryDriftModel model;
    model.seed = static_cast<std::uint64_t>(seed);
    // (the heading bias scales with the noise's standard deviations)
    model.bias *= driftScale;
    model.sp2 *= driftScale * driftScale;
    model.sh2 *= driftScale * driftScale;
    return datasets::writeMagneticRecording(recording, path, model);
}

TimedRun runImported(const datasets::MagneticImportResult& imported, const std::string& config,
                     const std::string& outDir, const std::string& mapIn, const std::string& mapOut) {
    TimedRun run;
    run.options.rawlog = imported.rawlog;
    run.options.groundTruth = imported.groundTruth;
    run.options.config = config.find('/') != std::string::npos
                             ? config
                             : std::string(LODESTONE_CONFIG_INI_DIR) + "/slam/" + config;
    run.options.outDir = outDir;
    run.options.mapIn = mapIn;
    run.options.mapOut = mapOut;
    run.options.quiet = true;
    std::ostringstream out, err;
    const auto t0 = std::chrono::steady_clock::now();
    run.result = slamapp::runSlam(run.options, out, err);
    run.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    run.errors = err.str();
    return run;
}
