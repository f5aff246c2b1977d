#pragma once
// A synthetic feature world for submap tests: 3D points with random ORB-like descriptors, seen
// by keyframes at known robot poses through a forward-looking camera.

#include <lodestone/vision/OrbFeatures.h>

#include <Eigen/Geometry>
#include <memory>
#include <random>

namespace lodestone::test {

struct FeatureWorld {
    std::vector<Eigen::Vector3d> points;  // world frame
    cv::Mat descriptors;                  // one 32-byte row per point

    /** `n` points on the walls of a 6 m x 6 m room, 0.2-2.2 m high. */
    static FeatureWorld room(int n, std::uint64_t seed) {
        FeatureWorld w;
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> u(-3, 3), h(0.2, 2.2);
        std::uniform_int_distribution<int> side(0, 3), byte(0, 255);
        w.descriptors.create(n, 32, CV_8U);
        for (int i = 0; i < n; ++i) {
            const double a = u(rng);
            const int s = side(rng);
            w.points.emplace_back(s == 0 ? 3.0 : s == 1 ? -3.0 : a, s == 2 ? 3.0 : s == 3 ? -3.0 : a, h(rng));
            for (int b = 0; b < 32; ++b) w.descriptors.at<std::uint8_t>(i, b) = static_cast<std::uint8_t>(byte(rng));
        }
        return w;
    }
};

/** The optical frame (x right, y down, z forward) of a camera looking along the robot's x axis,
 * 0.3 m above the base. */
inline Eigen::Isometry3d forwardCamera() {
    Eigen::Isometry3d C = Eigen::Isometry3d::Identity();
    C.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
    C.translation() = Eigen::Vector3d(0.1, 0, 0.3);
    return C;
}

inline Eigen::Isometry3d planarPose(double x, double y, double yaw) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(x, y, 0);
    return T;
}

/** What a keyframe at robot pose `X` sees: points in front of the camera within 0.3-5 m and a
 * 60-degree half-angle, with `noise` [m] on each coordinate and a few descriptor bits flipped. */
inline std::shared_ptr<vision::FrameFeatures> view(const FeatureWorld& w, const Eigen::Isometry3d& X,
                                                   double noise, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> n(0, noise);
    std::uniform_int_distribution<int> bit(0, 255);
    auto f = std::make_shared<vision::FrameFeatures>();
    const Eigen::Isometry3d worldToOptical = (X * forwardCamera()).inverse();
    std::vector<Eigen::Vector3f> pts;
    for (std::size_t i = 0; i < w.points.size(); ++i) {
        const Eigen::Vector3d p = worldToOptical * w.points[i];
        if (p.z() < 0.3 || p.z() > 5 || std::hypot(p.x(), p.y()) > p.z() * 1.7) continue;
        pts.push_back((p + Eigen::Vector3d(n(rng), n(rng), n(rng))).cast<float>());
        cv::Mat d = w.descriptors.row(static_cast<int>(i)).clone();
        for (int k = 0; k < 3; ++k) {
            const int b = bit(rng);
            d.at<std::uint8_t>(0, b / 8) ^= static_cast<std::uint8_t>(1 << (b % 8));
        }
        f->descriptors.push_back(d);
        f->keypoints.emplace_back(0.f, 0.f, 31.f);
    }
    f->points.resize(3, static_cast<Eigen::Index>(pts.size()));
    for (std::size_t i = 0; i < pts.size(); ++i) f->points.col(static_cast<Eigen::Index>(i)) = pts[i];
    f->detected = pts.size();
    return f;
}

}  // namespace lodestone::test
