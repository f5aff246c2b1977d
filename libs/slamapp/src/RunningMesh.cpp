#include "RunningMesh.h"

#include <lodestone/graphslam/Se3Pose.h>
#include <lodestone/odometry/RgbdObservationFrame.h>
#include <lodestone/outputs/RunFiles.h>

#include <mrpt/obs/CObservation3DRangeScan.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace lodestone::slamapp::detail {

namespace {

/** Re-fusions asked for after each new keyframe: the model follows the graph's corrections at
 * the run's pace; the rest wait for the end. */
constexpr std::size_t kRefusionsPerKeyframe = 2;

/** RGB-D frames kept until the node decider places their node. */
constexpr std::size_t kRecentFrames = 16;

}  // namespace

RunningMesh::RunningMesh(const dense::DenseParams& params, const std::string& outDir, graphslam::TNodeID firstNode)
    : params_(params), fusion_(params, outputs::pathIn(outDir, outputs::RunFile::Mesh) + ".frames"), next_(firstNode) {}

dense::KeyframeFusion::PoseOf RunningMesh::poseOf(const graphslam::SlamEngine& engine) const {
    return [this, &engine](std::uint64_t id) -> std::optional<Eigen::Isometry3d> {
        const auto node = engine.graph().nodes.find(id);
        // (a kidnapped segment not joined yet has no pose in the map's frame)
        if (node == engine.graph().nodes.end() || engine.relocalizer().groupOf(id) != 0) return std::nullopt;
        return graphslam::isometryOf(node->second) * opticalOnRobot_.at(id);
    };
}

void RunningMesh::observe(const mrpt::obs::CObservation::Ptr& obs, const graphslam::SlamEngine& engine) {
    // The node decider may place a keyframe's node after later observations: the recent
    // frames wait here for it.
    if (auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs)) {
        recent_.push_back(scan);
        if (recent_.size() > kRecentFrames) recent_.pop_front();
    }
    const auto& records = engine.nodes().records();
    bool added = false;
    for (; next_ < records.size(); ++next_) {
        const auto& record = records[next_];
        if (!record.keyframe) continue;
        const auto match = std::find_if(recent_.begin(), recent_.end(), [&](const auto& s) {
            return std::abs(mrpt::Clock::toDouble(s->timestamp) - record.timestamp) <= 1e-4;
        });
        if (match == recent_.end()) {
            // Not seen yet: wait for it; older than every frame kept: lost (counted).
            if (recent_.empty() || record.timestamp > mrpt::Clock::toDouble(recent_.back()->timestamp)) break;
            ++unmatched_;
            continue;
        }
        if (keyframes_++ % params_.everyKeyframe != 0) continue;
        const auto& scan = **match;
        const vision::RgbdFrame frame = odometry::frameFromObservation(scan);
        if (frame.depth.empty()) continue;
        cv::Mat colour;
        if (scan.hasIntensityImage && !scan.intensityImage.isEmpty()) {
            const cv::Mat img = scan.intensityImage.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
            if (img.type() == CV_8UC3 && img.size() == frame.depth.size()) colour = img;
        }
        opticalOnRobot_[next_] = odometry::opticalFrameOnRobot(scan.sensorPose);
        fusion_.add(next_, frame.depth, colour, frame.intrinsics, poseOf(engine)(next_));
        added = true;
    }
    if (added) fusion_.refuseMoved(poseOf(engine), kRefusionsPerKeyframe);
}

graphslam::JsonObject RunningMesh::finish(const graphslam::SlamEngine& engine, dense::Mesh& mesh, std::string& why) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto since = [](std::chrono::steady_clock::time_point t) {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    };
    const std::size_t atTheEnd = fusion_.refuseMoved(poseOf(engine));
    fusion_.stats();  // (waits for the worker)
    const double refuseSeconds = since(t0);
    const auto t1 = std::chrono::steady_clock::now();
    mesh = fusion_.extractMesh();
    const double extractSeconds = since(t1);
    const auto s = fusion_.stats();
    graphslam::JsonObject report;
    report.set("fusion", "while_running").set("volume", "blocks").set("keyframes", keyframes_ + unmatched_)
        .set("frames_fused", s.keyframes).set("frames_without_depth", s.withoutDepth)
        .set("refusions", s.refusions).set("refusions_at_the_end", atTheEnd)
        .set("voxel_size_m", params_.voxelSize).set("truncation_m", params_.truncation)
        .set("fused_depth_limit_m", params_.fusedDepthLimit())
        .set("fuse_seconds", s.fuseSeconds).set("store_seconds", s.spillSeconds)
        .set("store_mb", double(s.spillBytes) / (1 << 20)).set("volume_mb", double(s.volumeBytes) / (1 << 20))
        .set("end_refuse_seconds", refuseSeconds).set("extract_seconds", extractSeconds);
    why = opticalOnRobot_.empty() ? "the run has no keyframe on the map (no RGB-D frames tracked)"
          : s.keyframes == 0      ? "no keyframe's frame had usable depth"
                                  : "the fused frames made no surface";
    if (unmatched_ > 0) report.set("keyframes_without_their_frame", unmatched_);
    if (s.failures > 0) report.set("store_failures", s.failures).set("store_error", s.lastFailure);
    return report;
}

}  // namespace lodestone::slamapp::detail
