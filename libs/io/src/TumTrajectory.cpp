#include <lodestone/io/RawlogPaths.h>
#include <lodestone/io/TumTrajectory.h>
#include <mrpt/math/CQuaternion.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <exception>
#include <sstream>
#include <stdexcept>

namespace lodestone::io {

TumTrajectoryWriter::TumTrajectoryWriter(const std::string& path)
    : path_(path), out_(partialPath(path)), uncaught_at_start_(std::uncaught_exceptions()) {
    if (!out_) throw std::runtime_error(partialPath(path) + ": cannot create trajectory file");
    out_ << "# timestamp tx ty tz qx qy qz qw\n";
}

void TumTrajectoryWriter::write(double timestamp, const mrpt::poses::CPose3D& pose) {
    mrpt::math::CQuaternionDouble q;
    pose.getAsQuaternion(q);
    char line[256];
    std::snprintf(line, sizeof(line), "%.6f %.6f %.6f %.6f %.9f %.9f %.9f %.9f\n", timestamp,
                  pose.x(), pose.y(), pose.z(), q.x(), q.y(), q.z(), q.r());
    out_ << line;
    out_.flush();
    if (!out_) throw std::runtime_error(path_ + ": write error");
}

TumTrajectoryWriter::~TumTrajectoryWriter() {
    if (!out_.is_open()) return;
    if (std::uncaught_exceptions() > uncaught_at_start_) return;  // stays .partial
    try {
        close();
    } catch (...) {
    }
}

void TumTrajectoryWriter::close() {
    if (!out_.is_open()) return;
    out_.close();
    if (!out_) throw std::runtime_error(path_ + ": write error");
    commitPartial(path_);
}

std::vector<TumPose> readTumTrajectory(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw std::runtime_error(path + ": is a folder, not a trajectory file");
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open trajectory file");
    std::vector<TumPose> out;
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        const auto bad = [&](const std::string& why) {
            return std::runtime_error(path + ": line " + std::to_string(lineNo) + ": " + why);
        };
        std::istringstream s(line);
        double v[8];
        for (double& x : v) {
            std::string word;
            char* end = nullptr;
            if (!(s >> word) || (x = std::strtod(word.c_str(), &end), *end != '\0')) {
                throw bad("expected 'timestamp tx ty tz qx qy qz qw'");
            }
        }
        for (double x : v) {
            if (!std::isfinite(x)) throw bad("a value is not a finite number");
        }
        // Positions beyond any building: a unit mistake or a damaged file (and the squares
        // in an ATE would overflow).
        constexpr double kMaxCoordinate = 1e6;  // [m]
        for (int k = 1; k <= 3; ++k) {
            if (std::abs(v[k]) > kMaxCoordinate) throw bad("a position beyond 1e6 m");
        }
        const double norm = std::sqrt(v[4] * v[4] + v[5] * v[5] + v[6] * v[6] + v[7] * v[7]);
        if (!(norm > 1e-6)) throw bad("the quaternion is zero: no orientation");
        // (Equal times are fine: a recording's truth is written at every observation, and two
        // sensors may share a time.)
        if (!out.empty() && v[0] < out.back().timestamp) {
            throw bad("timestamp " + std::to_string(v[0]) + " is before the previous line's " +
                      std::to_string(out.back().timestamp) + " (a trajectory is in time order)");
        }
        const mrpt::math::CQuaternionDouble q(v[7] / norm, v[4] / norm, v[5] / norm, v[6] / norm);
        out.push_back({v[0], mrpt::poses::CPose3D(q, v[1], v[2], v[3])});
    }
    return out;
}

const TumPose* poseNearest(const std::vector<TumPose>& trajectory, double t, double maxDt) {
    const auto it = std::lower_bound(trajectory.begin(), trajectory.end(), t,
                                     [](const TumPose& p, double v) { return p.timestamp < v; });
    const TumPose* best = nullptr;
    for (auto c : {it, it == trajectory.begin() ? it : it - 1}) {
        if (c == trajectory.end()) continue;
        if (!best || std::abs(c->timestamp - t) < std::abs(best->timestamp - t)) best = &*c;
    }
    return best && std::abs(best->timestamp - t) <= maxDt ? best : nullptr;
}

}  // namespace lodestone::io
