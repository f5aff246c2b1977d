#include <lodestone/config/IniSection.h>
#include <lodestone/sim/FloorPlan.h>
#include <lodestone/sim/Scenario.h>

#include <cstdio>
#include <mrpt/config/CConfigFile.h>

#include <cmath>
#include <algorithm>
#include <filesystem>
#include <sstream>

namespace lodestone::sim {

using config::ConfigError;
using config::IniSection;

namespace {
constexpr double kDeg = M_PI / 180.0;

MountPose readMount(IniSection& s, const std::string& key, const MountPose& def) {
    const auto v = s.getDoubles(key, {def.x, def.y, def.z, def.yaw / kDeg}, 4);
    return {v[0], v[1], v[2], v[3] * kDeg};
}

Eigen::Vector2d readRange(IniSection& s, const std::string& key, const Eigen::Vector2d& def) {
    const auto v = s.getDoubles(key, {def.x(), def.y()}, 2);
    if (v[0] > v[1]) s.fail(key, "expected 'low high' with low <= high");
    return {v[0], v[1]};
}

SurfaceSpec readSurface(IniSection& s, const std::string& key, const std::string& def) {
    try {
        return SurfaceSpec::parse(s.getString(key, def));
    } catch (const std::invalid_argument& e) {
        s.fail(key, e.what());
    }
}

void positive(IniSection& s, const std::string& key, double v) {
    if (!(v > 0)) s.fail(key, "must be > 0");
}

void notNegative(IniSection& s, const std::string& key, double v) {
    if (!(v >= 0)) s.fail(key, "must be >= 0 (a standard deviation)");
}

void readWorld(IniSection& s, Scenario& sc) {
    sc.wallHeight = s.getDouble("wall_height", sc.wallHeight);
    positive(s, "wall_height", sc.wallHeight);
    sc.texturePixelsPerMetre = s.getDouble("texture_resolution", sc.texturePixelsPerMetre);
    positive(s, "texture_resolution", sc.texturePixelsPerMetre);
    const std::string filter = s.getString("texture_filter", "point");
    if (filter != "area" && filter != "point") s.fail("texture_filter", "must be area or point");
    sc.areaFilteredTextures = filter == "area";
    sc.floor = readSurface(s, "floor", "tiles");
    sc.ceiling = readSurface(s, "ceiling", "plain");
    sc.lampSpacing = s.getDouble("lamp_spacing", sc.lampSpacing);
    positive(s, "lamp_spacing", sc.lampSpacing);
    for (const auto& key : s.keysWithPrefix("wall_")) {
        if (key == "wall_height") continue;
        std::istringstream in(s.getString(key, ""));
        WallSpec w;
        w.name = key;
        std::string surface;
        in >> surface;
        try {
            w.surface = SurfaceSpec::parse(surface);
        } catch (const std::invalid_argument& e) {
            s.fail(key, e.what());
        }
        std::vector<double> xy;
        for (std::string word; in >> word;) {
            double v = 0;
            if (!config::parseDouble(word, v))
                s.fail(key, "expected coordinates, got '" + word + "'");
            xy.push_back(v);
        }
        if (xy.size() < 4 || xy.size() % 2) {
            s.fail(key, "expected '<surface> x1 y1 x2 y2 ...' (at least two points)");
        }
        for (std::size_t i = 0; i < xy.size(); i += 2) w.points.emplace_back(xy[i], xy[i + 1]);
        sc.walls.push_back(std::move(w));
    }
    if (sc.walls.empty())
        s.fail("wall_1", "a world needs walls (wall_<n> = <surface> x1 y1 x2 y2 ...)");
}

void readPath(IniSection& s, Scenario& sc) {
    const auto xy = s.getDoubles("waypoints", {});
    if (xy.size() < 4 || xy.size() % 2)
        s.fail("waypoints", "expected x1 y1 x2 y2 ... (>= 2 points)");
    for (std::size_t i = 0; i < xy.size(); i += 2)
        sc.motion.waypoints.emplace_back(xy[i], xy[i + 1]);
    sc.motion.laps = s.getInt("laps", 1);
    if (sc.motion.laps < 1) s.fail("laps", "must be >= 1");
}

void readRobot(IniSection& s, Scenario& sc) {
    auto& m = sc.motion;
    m.speed = s.getDouble("speed", m.speed);
    m.turnRate = s.getDouble("turn_rate_deg", m.turnRate / kDeg) * kDeg;
    m.wheelBase = s.getDouble("wheel_base", m.wheelBase);
    m.wheelRadius = s.getDouble("wheel_radius", m.wheelRadius);
    sc.robotRadius = s.getDouble("radius", sc.robotRadius);
    for (const char* k : {"speed", "turn_rate_deg", "wheel_base", "wheel_radius", "radius"}) {
        if (s.has(k)) positive(s, k, s.getDouble(k, 1));
    }
}

void readEncoders(IniSection& s, EncoderSpec& e) {
    e.label = s.getString("label", e.label);
    e.rate = s.getDouble("rate", e.rate);
    positive(s, "rate", e.rate);
    e.ticksPerRev = s.getDouble("ticks_per_rev", e.ticksPerRev);
    positive(s, "ticks_per_rev", e.ticksPerRev);
    e.slipStd = s.getDouble("slip_std", e.slipStd);
    notNegative(s, "slip_std", e.slipStd);
    e.leftScale = s.getDouble("left_scale", e.leftScale);
    e.rightScale = s.getDouble("right_scale", e.rightScale);
    positive(s, "left_scale", e.leftScale);
    positive(s, "right_scale", e.rightScale);
    e.wheelDropLabel = s.getString("wheel_drop_label", e.wheelDropLabel);
}

void readCamera(IniSection& s, CameraSpec& c) {
    c.enabled = s.getBool("enabled", c.enabled);
    c.label = s.getString("label", c.label);
    c.rate = s.getDouble("rate", c.rate);
    positive(s, "rate", c.rate);
    c.width = s.getInt("width", c.width);
    c.height = s.getInt("height", c.height);
    if (c.width < 16 || c.height < 16) s.fail("width", "image must be at least 16x16");
    if (c.width > CameraSpec::kMaxSide || c.height > CameraSpec::kMaxSide) {
        s.fail("width", "image must be at most " + std::to_string(CameraSpec::kMaxSide) +
                            " pixels a side");
    }
    // Intrinsics default to the Kinect's, scaled to the image size.
    const double scale = c.width / 640.0;
    c.fx = s.getDouble("fx", 570.3 * scale);
    c.fy = s.getDouble("fy", 570.3 * scale);
    c.cx = s.getDouble("cx", (c.width - 1) / 2.0);
    c.cy = s.getDouble("cy", (c.height - 1) / 2.0);
    c.pose = readMount(s, "pose", c.pose);
    c.minRange = s.getDouble("min_range", c.minRange);
    c.maxRange = s.getDouble("max_range", c.maxRange);
    if (c.minRange >= c.maxRange) s.fail("max_range", "must exceed min_range");
    c.depthNoise = s.getDouble("depth_noise", c.depthNoise);
    notNegative(s, "depth_noise", c.depthNoise);
    c.disparityStep = s.getDouble("disparity_step", c.disparityStep);
    notNegative(s, "disparity_step", c.disparityStep);
    c.maxIncidence = s.getDouble("max_incidence_deg", c.maxIncidence / kDeg) * kDeg;
    c.rgbNoise = s.getDouble("rgb_noise", c.rgbNoise);
    notNegative(s, "rgb_noise", c.rgbNoise);
    c.externalImages = s.getBool("external_images", c.externalImages);
    c.imageFormat = s.getString("image_format", c.imageFormat);
    if (c.imageFormat != "png" && c.imageFormat != "jpg") s.fail("image_format", "must be png or jpg");
    c.jpegQuality = s.getInt("jpeg_quality", c.jpegQuality);
    if (c.jpegQuality < 1 || c.jpegQuality > 100) s.fail("jpeg_quality", "must be 1..100");
}

void readMagnetometer(IniSection& s, MagnetometerSpec& m) {
    m.label = s.getString("label", s.section());
    m.rate = s.getDouble("rate", m.rate);
    positive(s, "rate", m.rate);
    m.pose = readMount(s, "pose", m.pose);
    m.noiseStd = s.getDouble("noise_std", m.noiseStd);
    notNegative(s, "noise_std", m.noiseStd);
    const auto b = s.getDoubles("bias", {0, 0, 0}, 3);
    m.bias = {b[0], b[1], b[2]};
}

void readGyro(IniSection& s, GyroSpec& g) {
    g.label = s.getString("label", g.label);
    g.rate = s.getDouble("rate", g.rate);
    positive(s, "rate", g.rate);
    g.pose = readMount(s, "pose", g.pose);
    g.noiseStd = s.getDouble("noise_std_deg", g.noiseStd / kDeg) * kDeg;
    notNegative(s, "noise_std_deg", g.noiseStd);
    g.biasSigma = s.getDouble("bias_sigma_deg", g.biasSigma / kDeg) * kDeg;
    notNegative(s, "bias_sigma_deg", g.biasSigma);
    g.accelNoiseStd = s.getDouble("accel_noise_std", g.accelNoiseStd);
    notNegative(s, "accel_noise_std", g.accelNoiseStd);
    g.accelBiasSigma = s.getDouble("accel_bias_sigma", g.accelBiasSigma);
    notNegative(s, "accel_bias_sigma", g.accelBiasSigma);
}

void readField(IniSection& s, FieldSpec& f) {
    f.earthMagnitude = s.getDouble("earth_magnitude", f.earthMagnitude);
    f.inclination = s.getDouble("inclination_deg", f.inclination / kDeg) * kDeg;
    f.declination = s.getDouble("declination_deg", f.declination / kDeg) * kDeg;
    f.wallSpacing = s.getDouble("wall_spacing", f.wallSpacing);
    f.wallMoment = readRange(s, "wall_moment", f.wallMoment);
    f.floorDensity = s.getDouble("floor_density", f.floorDensity);
    f.floorDepth = readRange(s, "floor_depth", f.floorDepth);
    f.floorMoment = readRange(s, "floor_moment", f.floorMoment);
    for (const auto& key : s.keysWithPrefix("line_")) {
        const auto v = s.getDoubles(key, {}, 10);
        if (v[9] <= 0) s.fail(key, "spacing (10th number) must be > 0");
        f.lines.push_back({{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}, v[9]});
    }
    for (const auto& key : s.keysWithPrefix("dipole_")) {
        const auto v = s.getDoubles(key, {}, 6);
        f.dipoles.emplace_back(Eigen::Vector3d(v[0], v[1], v[2]),
                               Eigen::Vector3d(v[3], v[4], v[5]));
    }
    // A quieter (or livelier) building: the same anomalies, every moment scaled - the same
    // draws, so the same places, with less contrast between them.
    const double scale = s.getDouble("anomaly_scale", 1.0);
    if (!(scale >= 0)) s.fail("anomaly_scale", "must be >= 0");
    f.wallMoment *= scale;
    f.floorMoment *= scale;
    for (auto& line : f.lines) line.momentPerMetre *= scale;
    for (auto& dipole : f.dipoles) dipole.second *= scale;
}

void readKidnaps(IniSection& s, Scenario& sc) {
    for (const auto& key : s.keysWithPrefix("kidnap_")) {
        const auto v = s.getDoubles(key, {}, 5);
        KidnapSpec k;
        k.name = sc.source + " [kidnap] key '" + key + "'";
        k.start = v[0];
        k.duration = v[1];
        k.putDown = {v[2], v[3], v[4] * kDeg, 0};
        if (k.start < 0 || k.duration <= 0) s.fail(key, "expected start >= 0 and duration > 0");
        sc.kidnaps.push_back(k);
    }
}

std::string xyText(const Eigen::Vector2d& p) {
    std::ostringstream o;
    o << "(" << p.x() << ", " << p.y() << ")";
    return o.str();
}

// Geometry checks: no leg of the loop through a wall, no put-down on or in a wall.
void validateGeometry(const Scenario& sc) {
    FloorPlan plan;
    for (const auto& w : sc.walls) {
        for (std::size_t i = 0; i + 1 < w.points.size(); ++i)
            plan.addWall({w.points[i], w.points[i + 1]});
    }
    const auto& wp = sc.motion.waypoints;
    for (std::size_t i = 0; i < wp.size(); ++i) {
        const std::size_t j = (i + 1) % wp.size();
        if (plan.blocks(wp[i], wp[j], sc.robotRadius)) {
            throw ConfigError(sc.source + " [path] key 'waypoints': the leg from waypoint " +
                              std::to_string(i + 1) + " " + xyText(wp[i]) + " to waypoint " +
                              std::to_string(j + 1) + " " + xyText(wp[j]) +
                              " passes through a wall (or closer than the robot radius)");
        }
    }
    for (const auto& k : sc.kidnaps) {
        const Eigen::Vector2d p(k.putDown.x, k.putDown.y);
        if (plan.clearance(p) < sc.robotRadius) {
            throw ConfigError(k.name + ": put-down pose " + xyText(p) +
                              " is inside a wall (closer than the robot radius)");
        }
    }
}
}  // namespace

void CameraSpec::resize(int newWidth, int newHeight) {
    const double scale = newWidth / static_cast<double>(width);
    fx *= scale;
    fy *= scale;
    width = newWidth;
    height = newHeight;
    cx = (width - 1) / 2.0;
    cy = (height - 1) / 2.0;
}

bool CameraSpec::override(const std::string& widthHeightRate) {
    int w = 0, h = 0;
    double hz = 0;
    char tail = 0;
    if (std::sscanf(widthHeightRate.c_str(), "%dx%d@%lf%c", &w, &h, &hz, &tail) != 3 || w < 16 ||
        h < 16 || w > kMaxSide || h > kMaxSide || !(hz > 0) || hz > 1000) {
        return false;
    }
    resize(w, h);
    rate = hz;
    return true;
}

bool CameraSpec::setImageFormat(const std::string& text) {
    if (text == "png" || text == "jpg") {
        imageFormat = text;
        return true;
    }
    int q = 0;
    char tail = 0;
    if (std::sscanf(text.c_str(), "jpg:%d%c", &q, &tail) == 1 && q >= 1 && q <= 100) {
        imageFormat = "jpg";
        jpegQuality = q;
        return true;
    }
    return false;
}

Scenario Scenario::load(const std::string& iniPath) {
    if (!std::filesystem::is_regular_file(iniPath)) {
        throw ConfigError(iniPath + ": no such scenario file");
    }
    mrpt::config::CConfigFile cfg(iniPath);
    std::vector<std::string> sections;
    cfg.getAllSections(sections);
    std::set<std::string> allowed = {"scenario", "world",          "path",   "robot", "encoders",
                                     "camera",   "magnetic_field", "kidnap", "gyro"};
    for (const auto& name : sections) {
        if (name.rfind("magnetometer_", 0) == 0) allowed.insert(name);
    }
    config::checkSections(cfg, allowed, iniPath);

    Scenario sc;
    sc.source = iniPath;
    const auto section = [&](const std::string& name, auto&& read) {
        IniSection s(cfg, name, iniPath);
        read(s);
        s.finish();
    };
    section("scenario", [&](IniSection& s) {
        sc.name = s.getString("name", std::filesystem::path(iniPath).stem().string());
        const int seed = s.getInt("seed", 1);
        if (seed < 0) s.fail("seed", "must be >= 0");
        sc.seed = static_cast<std::uint64_t>(seed);
        if (s.has("world_seed")) {
            const int world = s.getInt("world_seed", 1);
            if (world < 0) s.fail("world_seed", "must be >= 0");
            sc.worldSeed = static_cast<std::uint64_t>(world);
        }
        sc.startTime = s.getDouble("start_time", sc.startTime);
    });
    section("world", [&](IniSection& s) { readWorld(s, sc); });
    section("path", [&](IniSection& s) { readPath(s, sc); });
    section("robot", [&](IniSection& s) { readRobot(s, sc); });
    section("encoders", [&](IniSection& s) { readEncoders(s, sc.encoders); });
    section("camera", [&](IniSection& s) { readCamera(s, sc.camera); });
    section("magnetic_field", [&](IniSection& s) { readField(s, sc.field); });
    section("kidnap", [&](IniSection& s) { readKidnaps(s, sc); });
    if (std::find(sections.begin(), sections.end(), "gyro") != sections.end()) {
        GyroSpec g;
        section("gyro", [&](IniSection& s) { readGyro(s, g); });
        sc.gyro = g;
    }
    for (const auto& name : sections) {
        if (name.rfind("magnetometer_", 0) != 0) continue;
        MagnetometerSpec m;
        section(name, [&](IniSection& s) { readMagnetometer(s, m); });
        sc.magnetometers.push_back(m);
    }
    validateGeometry(sc);
    return sc;
}

}  // namespace lodestone::sim
