// --mesh: the dense model into mesh.ply. Fused while the run went (RunningMesh: a live run, or
// [dense] fusion = while_running), it is only written here. Otherwise, after the last
// optimization the source is read once more (the rawlog again, or the scenario simulated again
// with its seed) and every keyframe's RGB-D frame is fused at its node's optimized pose
// (dense::TsdfFusion), then meshed. Frames are not held through the run: a second pass costs
// reading, not memory.
#include "RunParts.h"

#include <lodestone/dense/TsdfFusion.h>
#include <lodestone/graphslam/Se3Pose.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/outputs/RunFiles.h>
#include <lodestone/sim/Scenario.h>
#include <lodestone/sim/SimulatorSource.h>
#include <lodestone/slamapp/KeyframeMeshPass.h>

#include <mrpt/config/CConfigFile.h>

#include <chrono>
#include <cmath>
#include <map>

namespace lodestone::slamapp::detail {

namespace {

double since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/** The keyframes to fuse, by their frame's time: node ID (those of the map's group only: a
 * kidnapped segment never joined has no pose in the map's frame). */
std::map<double, graphslam::TNodeID> keyframesByTime(const graphslam::SlamEngine& engine, int every) {
    std::map<double, graphslam::TNodeID> out;
    int k = 0;
    const auto& records = engine.nodes().records();
    for (graphslam::TNodeID id = engine.mapNodes(); id < records.size(); ++id) {
        if (!records[id].keyframe || !engine.graph().nodes.count(id)) continue;
        if (engine.relocalizer().groupOf(id) != 0) continue;
        if (k++ % every == 0) out[records[id].timestamp] = id;
    }
    return out;
}

}  // namespace

graphslam::JsonObject writeMesh(const RunInputs& in, const LoopOutcome& loop, const SlamRunOptions& options,
                                std::ostream& err) {
    const auto t0 = std::chrono::steady_clock::now();
    graphslam::JsonObject report;
    const auto skip = [&](const std::string& why) {
        err << "lodestone-slam: --mesh: no mesh.ply: " << why << "\n";
        return report.set("written", false).set("why", why);
    };
    if (loop.runningMesh) {
        report = *loop.runningMesh;
        if (loop.mesh.empty()) return skip(loop.runningMeshWhy);
        const auto t1 = std::chrono::steady_clock::now();
        dense::writeMeshPly(outputs::pathIn(options.outDir, outputs::RunFile::Mesh), loop.mesh);
        return report.set("written", true).set("vertices", loop.mesh.vertices.size()).set("triangles", loop.mesh.triangles.size())
            .set("write_seconds", since(t1));
    }
    const auto& engine = *in.engine;
    const dense::DenseParams params = dense::DenseParams::read(mrpt::config::CConfigFile(options.config));
    const auto keyframes = keyframesByTime(engine, params.everyKeyframe);
    if (keyframes.empty()) return skip("the run has no keyframe on the map (no RGB-D frames tracked)");
    std::unique_ptr<io::DataSource> source;
    if (!options.scenario.empty()) {
        const auto scenario = sim::Scenario::load(options.scenario);
        source = std::make_unique<sim::SimulatorSource>(scenario, scenario.seed);
    } else {
        source = std::make_unique<io::RawlogSource>(options.rawlog);
    }
    std::map<double, Eigen::Isometry3d> robotPoses;
    for (const auto& [t, id] : keyframes) robotPoses[t] = graphslam::isometryOf(engine.graph().nodes.at(id));
    dense::TsdfFusion fusion(params);
    const KeyframeMeshPass pass = fuseKeyframes(*source, robotPoses, fusion);
    const double passSeconds = since(t0);
    report.set("keyframes", keyframes.size()).set("frames_found", pass.framesFound)
        .set("frames_fused", fusion.framesFused()).set("frames_without_depth", pass.withoutDepth)
        .set("pixels_fused", pass.pixels)
        .set("fusion", "after_run")
        .set("volume", params.volume == dense::DenseParams::Volume::Open3d ? "open3d" : "blocks")
        .set("voxel_size_m", params.voxelSize).set("truncation_m", params.truncation)
        .set("fused_depth_limit_m", params.fusedDepthLimit());
    if (fusion.framesFused() == 0) return skip("no keyframe's frame had usable depth");
    const auto t2 = std::chrono::steady_clock::now();
    const dense::Mesh mesh = fusion.extractMesh();
    const double extractSeconds = since(t2);
    if (mesh.empty()) return skip("the fused frames made no surface");
    const auto t3 = std::chrono::steady_clock::now();
    dense::writeMeshPly(outputs::pathIn(options.outDir, outputs::RunFile::Mesh), mesh);
    // (the pass: reading the source again and fusing; then meshing and writing)
    if (fusion.memoryBytes() > 0) report.set("volume_mb", double(fusion.memoryBytes()) / (1 << 20));
    return report.set("written", true).set("vertices", mesh.vertices.size()).set("triangles", mesh.triangles.size())
        .set("pass_seconds", passSeconds).set("integrate_seconds", pass.integrateSeconds)
        .set("extract_seconds", extractSeconds).set("write_seconds", since(t3)).set("seconds", since(t0));
}

}  // namespace lodestone::slamapp::detail
