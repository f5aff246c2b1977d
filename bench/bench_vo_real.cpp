// RGB-D VO on the real Kinect frames of ../shared/data/rgbd/3dmatch (read in place): accuracy of
// frames 0->1 and 0->2 against the given poses, and time per 640x480 frame split into decode
// (PNG colour + depth), ORB, matching and RANSAC, beside OpenCV's ORB detect+compute alone on
// the same frames (the floor). Prints markdown table rows.
//   bench_vo_real [DATA_DIR] [REPEATS]
#include <lodestone/vision/RgbdVisualOdometry.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

using namespace lodestone::vision;
namespace fs = std::filesystem;

namespace {
double ms(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

RgbdFrame load(const fs::path& dir, int i, double& decodeMs) {
    char name[64];
    std::snprintf(name, sizeof(name), "seq-01/frame-%06d", i);
    const auto t0 = std::chrono::steady_clock::now();
    const cv::Mat colour = cv::imread((dir / (std::string(name) + ".color.png")).string());
    const cv::Mat depth =
        cv::imread((dir / (std::string(name) + ".depth.png")).string(), cv::IMREAD_UNCHANGED);
    RgbdFrame f;
    cv::cvtColor(colour, f.gray, cv::COLOR_BGR2GRAY);
    f.depth = depthToMetres(depth, 0.001);
    decodeMs += ms(t0);
    f.intrinsics = {570.342205, 570.342205, 320.0, 240.0, 640, 480};
    return f;
}

Eigen::Isometry3d pose(const fs::path& dir, int i) {
    char name[64];
    std::snprintf(name, sizeof(name), "seq-01/frame-%06d.pose.txt", i);
    std::ifstream in(dir / name);
    Eigen::Isometry3d T;
    for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) in >> T.matrix()(r, c);
    }
    return T;
}
}  // namespace

int main(int argc, char** argv) {
    const fs::path dir = argc > 1 ? fs::path(argv[1]) : fs::path("../shared/data/rgbd/3dmatch");
    const int repeats = argc > 2 ? std::atoi(argv[2]) : 20;
    if (!fs::exists(dir / "seq-01")) {
        std::cerr << "bench_vo_real: real data absent: " << dir << "\n";
        return 1;
    }
    // Accuracy: features alone, then features and depth solved as one.
    for (const bool depth : {false, true}) {
        for (const int other : {1, 2}) {
            double unused = 0;
            RgbdVisualOdometry::Params params;
            params.depthAlignment = params.depthWithFeatures = depth;
            RgbdVisualOdometry vo(params);
            vo.process(load(dir, 0, unused));
            const auto r = vo.process(load(dir, other, unused));
            const Eigen::Isometry3d err =
                (pose(dir, 0).inverse() * pose(dir, other)).inverse() * r.T_ref_cur;
            std::printf(
                "| accuracy%s | 0 -> %d | %s | %zu inliers of %zu matches | %.2f cm | %.3f deg |\n",
                depth ? " (features + depth)" : "", other,
                r.success ? "tracked" : toString(r.failure), r.inliers, r.matches,
                100 * err.translation().norm(),
                Eigen::AngleAxisd(err.rotation()).angle() * 180 / M_PI);
        }
    }
    // Time: the five frames in a loop, as a sequence.
    const int frames[] = {0, 1, 2, 0, 1};
    double decode = 0, orb = 0, match = 0, ransac = 0, floor = 0;
    int n = 0;
    RgbdVisualOdometry vo;
    auto orbOnly = cv::ORB::create(vo.params().orb.features);
    for (int rep = 0; rep < repeats; ++rep) {
        for (int i : frames) {
            const RgbdFrame f = load(dir, i, decode);
            const auto r = vo.process(f);
            orb += r.timing.orb;
            match += r.timing.matching;
            ransac += r.timing.ransac;
            std::vector<cv::KeyPoint> kp;
            cv::Mat d;
            const auto t0 = std::chrono::steady_clock::now();
            orbOnly->detectAndCompute(f.gray, cv::noArray(), kp, d);
            floor += ms(t0);
            ++n;
        }
    }
    const double total = (decode + orb + match + ransac) / n;
    std::printf(
        "| time | %d frames | decode %.2f | ORB %.2f | matching %.2f | RANSAC %.2f | total %.2f ms "
        "| ORB alone %.2f ms | VO step / ORB alone %.2f | whole / ORB alone %.2f |\n",
        n, decode / n, orb / n, match / n, ransac / n, total, floor / n,
        (orb + match + ransac) / floor, total / (floor / n));
    return 0;
}
