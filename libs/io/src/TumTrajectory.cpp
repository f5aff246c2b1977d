#include <lodestone/io/TumTrajectory.h>
#include <mrpt/math/CQuaternion.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace lodestone::io {

TumTrajectoryWriter::TumTrajectoryWriter(const std::string& path) : path_(path), out_(path) {
    if (!out_) throw std::runtime_error(path + ": cannot create trajectory file");
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

std::vector<TumPose> readTumTrajectory(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open trajectory file");
    std::vector<TumPose> out;
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        std::istringstream s(line);
        double v[8];
        for (double& x : v) s >> x;
        if (!s || !std::isfinite(v[0])) {
            throw std::runtime_error(path + ": line " + std::to_string(lineNo) +
                                     ": expected 'timestamp tx ty tz qx qy qz qw'");
        }
        const mrpt::math::CQuaternionDouble q(v[7], v[4], v[5], v[6]);
        out.push_back({v[0], mrpt::poses::CPose3D(q, v[1], v[2], v[3])});
    }
    return out;
}

}  // namespace lodestone::io
