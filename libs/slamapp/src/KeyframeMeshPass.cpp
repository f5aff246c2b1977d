#include <lodestone/odometry/RgbdObservationFrame.h>
#include <lodestone/slamapp/KeyframeMeshPass.h>

#include <mrpt/obs/CObservation3DRangeScan.h>

#include <chrono>
#include <cmath>

namespace lodestone::slamapp {

KeyframeMeshPass fuseKeyframes(io::DataSource& source, const std::map<double, Eigen::Isometry3d>& robotPoseByTime,
                               dense::TsdfFusion& fusion) {
    KeyframeMeshPass pass;
    pass.keyframes = robotPoseByTime.size();
    if (robotPoseByTime.empty()) return pass;
    const double last = robotPoseByTime.rbegin()->first;
    while (auto obs = source.next()) {
        const double t = mrpt::Clock::toDouble(obs->timestamp);
        if (t > last + 1e-3) break;
        const auto* scan = dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(obs.get());
        if (!scan) continue;
        const auto it = robotPoseByTime.lower_bound(t - 1e-4);
        if (it == robotPoseByTime.end() || std::abs(it->first - t) > 1e-4) continue;
        ++pass.framesFound;
        const vision::RgbdFrame frame = odometry::frameFromObservation(*scan);
        if (frame.depth.empty()) {
            ++pass.withoutDepth;
            continue;
        }
        cv::Mat colour;
        if (scan->hasIntensityImage && !scan->intensityImage.isEmpty()) {
            const cv::Mat img = scan->intensityImage.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
            if (img.type() == CV_8UC3 && img.size() == frame.depth.size()) colour = img;
        }
        const auto t0 = std::chrono::steady_clock::now();
        const std::size_t fused = fusion.integrate(frame.depth, colour, frame.intrinsics,
                                                   it->second * odometry::opticalFrameOnRobot(scan->sensorPose));
        pass.integrateSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        pass.pixels += fused;
        pass.withoutDepth += fused == 0;
    }
    return pass;
}

}  // namespace lodestone::slamapp
