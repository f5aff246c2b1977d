#include <lodestone/datasets/DepthRegistration.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace lodestone::datasets {

Eigen::Isometry3d DepthRegistration::parsePose(const std::string& text) {
    double v[7];
    std::istringstream s(text);
    bool ok = true;
    for (int i = 0; i < 7 && ok; ++i) {
        char comma = ',';
        ok = static_cast<bool>(s >> v[i]) && std::isfinite(v[i]) && (i == 6 || (s >> comma && comma == ','));
    }
    ok = ok && s.peek() == EOF;
    const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
    if (!ok || !(q.norm() > 1e-9)) {
        throw std::invalid_argument("depth-to-colour pose '" + text +
                                    "': expected tx,ty,tz,qx,qy,qz,qw (metres, a non-zero quaternion)");
    }
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = q.normalized().toRotationMatrix();
    T.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
    return T;
}

cv::Mat registerDepthToColour(const cv::Mat& depth16, const DepthRegistration& r,
                              const PinholeIntrinsics& colour, cv::Size colourSize,
                              double depthScale, unsigned invalidFrom) {
    CV_Assert(depth16.type() == CV_16UC1);
    cv::Mat out(colourSize, CV_16UC1, cv::Scalar(0));
    const Eigen::Matrix3d R = r.colourFromDepth.linear();
    const Eigen::Vector3d t = r.colourFromDepth.translation();
    const auto& kd = r.depth;
    for (int v = 0; v < depth16.rows; ++v) {
        const auto* row = depth16.ptr<std::uint16_t>(v);
        for (int u = 0; u < depth16.cols; ++u) {
            const unsigned raw = row[u];
            if (raw == 0 || raw >= invalidFrom) continue;
            const double z = raw / depthScale;
            const Eigen::Vector3d p(((u - kd.cx) / kd.fx) * z, ((v - kd.cy) / kd.fy) * z, z);
            const Eigen::Vector3d q = R * p + t;
            if (!(q.z() > 0)) continue;
            const long uc = std::lround(colour.fx * q.x() / q.z() + colour.cx);
            const long vc = std::lround(colour.fy * q.y() / q.z() + colour.cy);
            if (uc < 0 || vc < 0 || uc >= colourSize.width || vc >= colourSize.height) continue;
            const double scaled = std::round(q.z() * depthScale);
            if (scaled < 1 || scaled >= std::min<double>(invalidFrom, 65535)) continue;
            auto& cell = out.at<std::uint16_t>(static_cast<int>(vc), static_cast<int>(uc));
            const auto value = static_cast<std::uint16_t>(scaled);
            if (cell == 0 || value < cell) cell = value;  // the nearest surface hides the rest
        }
    }
    return out;
}

}  // namespace lodestone::datasets
