#include <lodestone/datasets/MagneticRecordingVariants.h>
#include <lodestone/magnetic/PassNoiseEstimate.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <stdexcept>

namespace lodestone::datasets {

namespace {

Eigen::Vector3d toWorld(const MagneticRecordingSample& s) {
    const double c = std::cos(s.heading), n = std::sin(s.heading);
    return {c * s.field.x - n * s.field.y, n * s.field.x + c * s.field.y, s.field.z};
}

void setFromWorld(MagneticRecordingSample& s, const Eigen::Vector3d& w) {
    const double c = std::cos(s.heading), n = std::sin(s.heading);
    s.field = {c * w.x() + n * w.y(), -n * w.x() + c * w.y(), w.z()};
}

double numberAfter(const std::string& spec, const std::string& prefix) {
    std::size_t used = 0;
    double v = NAN;
    try {
        v = std::stod(spec.substr(prefix.size()), &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != spec.size() - prefix.size() || !(v > 0))
        throw std::invalid_argument("variant '" + spec + "': expected " + prefix + "<number > 0>");
    return v;
}

MagneticRecording withNoise(MagneticRecording rec, double sigma, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0, sigma);
    for (auto& s : rec.samples) {
        s.field.x += n(rng);
        s.field.y += n(rng);
        s.field.z += n(rng);
    }
    return rec;
}

MagneticRecording quieter(MagneticRecording rec, double scale, unsigned seed) {
    const double measured = passRepeatability(rec);
    const double repeatability =
        std::max(std::isfinite(measured) ? measured : 0.0, kRepeatabilityFloor);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& s : rec.samples) mean += toWorld(s);
    mean /= double(rec.samples.size());
    for (auto& s : rec.samples) setFromWorld(s, mean + scale * (toWorld(s) - mean));
    rec.name += " quiet " + std::to_string(scale);
    return withNoise(std::move(rec), repeatability * std::sqrt(std::max(0.0, 1 - scale * scale)),
                     seed);
}

MagneticRecording resampled(const MagneticRecording& rec, double rate) {
    MagneticRecording out = rec;
    out.samples.clear();
    const auto& in = rec.samples;
    std::size_t k = 0;
    for (double t = in.front().t; t <= in.back().t; t += 1.0 / rate) {
        while (k + 2 < in.size() && in[k + 1].t <= t) ++k;
        const auto& a = in[k];
        const auto& b = in[k + 1];
        const double f = std::clamp((t - a.t) / (b.t - a.t), 0.0, 1.0);
        MagneticRecordingSample s;
        s.t = t;
        s.x = a.x + f * (b.x - a.x);
        s.y = a.y + f * (b.y - a.y);
        s.heading = a.heading + f * (b.heading - a.heading);  // (headings are unwrapped)
        setFromWorld(s, toWorld(a) + f * (toWorld(b) - toWorld(a)));
        out.samples.push_back(s);
    }
    return out;
}

MagneticRecording inUnit(const MagneticRecording& rec, const std::string& unitText,
                         const std::string& scratch, unsigned seed) {
    const auto unit = obs::MagneticUnit::parse(unitText);
    std::filesystem::create_directories(scratch);
    const std::string csv = scratch + "/variant_" + std::to_string(seed) + ".csv";
    writeKokWalk(rec, csv, unit);
    auto read = readKokWalk(csv, unit);
    std::filesystem::remove(csv);
    read.name = rec.name;
    read.calibrated = rec.calibrated;
    return read;
}

}  // namespace

double passRepeatability(const MagneticRecording& rec, double radius, double gap) {
    // The same pairs as a map's own passes give (magnetic::passRepeatabilityAcrossPasses), by
    // the reference positions and the walk along them.
    const auto& s = rec.samples;
    std::vector<Eigen::Vector2d> positions(s.size());
    std::vector<Eigen::Vector3d> world(s.size());
    std::vector<double> walk(s.size(), 0.0);
    for (std::size_t i = 0; i < s.size(); ++i) {
        positions[i] = {s[i].x, s[i].y};
        world[i] = toWorld(s[i]);
        if (i > 0) walk[i] = walk[i - 1] + (positions[i] - positions[i - 1]).norm();
    }
    const auto sigma = magnetic::passRepeatabilityAcrossPasses(
        positions, world, walk, std::vector<int>(s.size(), 0), radius, gap, 10);
    return sigma ? *sigma : NAN;
}

MagneticRecording magneticVariant(const MagneticRecording& rec, const std::string& spec,
                                  unsigned seed, const std::string& scratch) {
    if (spec.empty() || spec == "original") return rec;
    if (spec.rfind("quiet:", 0) == 0) return quieter(rec, numberAfter(spec, "quiet:"), seed);
    if (spec.rfind("noise:", 0) == 0) return withNoise(rec, numberAfter(spec, "noise:"), seed);
    if (spec.rfind("rate:", 0) == 0) return resampled(rec, numberAfter(spec, "rate:"));
    if (spec == "gauss" || spec.rfind("normalized:", 0) == 0)
        return inUnit(rec, spec, scratch, seed);
    throw std::invalid_argument("unknown variant '" + spec +
                                "' (original, quiet:A, gauss, normalized:F, rate:HZ, noise:S)");
}

}  // namespace lodestone::datasets
