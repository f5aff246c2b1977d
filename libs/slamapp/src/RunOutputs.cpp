#include "RunParts.h"

#include <lodestone/eval/FieldMapPlot.h>
#include <lodestone/eval/TrajectoryError.h>
#include <lodestone/eval/TrajectoryPlot.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/outputs/RunFiles.h>
#include <lodestone/slamapp/GraphPlot.h>
#include <lodestone/slamapp/RunOutputs.h>

#include <opencv2/imgcodecs.hpp>

#include <Eigen/Cholesky>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace lodestone::slamapp {

using graphslam::Graph;
using graphslam::NodeStore;
using graphslam::TNodeID;

std::size_t writeMapPly(const std::string& path, const Graph& graph, const NodeStore& nodes) {
    std::size_t count = 0;
    for (TNodeID id = 0; id < nodes.size(); ++id) {
        const auto& r = nodes.at(id);
        if (r.cloud && graph.nodes.count(id)) count += r.cloud->points.size();
    }
    std::ofstream out(path, std::ios::binary);
    if (!out) throw std::runtime_error(path + ": cannot write the map");
    out << "ply\nformat binary_little_endian 1.0\ncomment Lodestone keyframe map\n"
        << "element vertex " << count << "\n"
        << "property float x\nproperty float y\nproperty float z\n"
        << "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
    for (TNodeID id = 0; id < nodes.size(); ++id) {
        const auto& r = nodes.at(id);
        if (!r.cloud || !graph.nodes.count(id)) continue;
        const mrpt::poses::CPose3D& pose = graph.nodes.at(id);
        for (const auto& p : r.cloud->points) {
            double gx, gy, gz;
            pose.composePoint(p.x, p.y, p.z, gx, gy, gz);
            const float xyz[3] = {static_cast<float>(gx), static_cast<float>(gy),
                                  static_cast<float>(gz)};
            out.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
            const std::uint8_t rgb[3] = {p.r, p.g, p.b};
            out.write(reinterpret_cast<const char*>(rgb), sizeof rgb);
        }
    }
    if (!out) throw std::runtime_error(path + ": write failed");
    return count;
}

std::vector<io::TumPose> nodeTrajectory(const Graph& graph, const NodeStore& nodes) {
    std::vector<io::TumPose> out;
    for (TNodeID id = 0; id < nodes.size(); ++id) {
        if (graph.nodes.count(id)) out.push_back({nodes.at(id).timestamp, graph.nodes.at(id)});
    }
    return out;
}

void writeTrajectory(const std::string& path, const std::vector<io::TumPose>& trajectory) {
    io::TumTrajectoryWriter w(path);
    for (const auto& p : trajectory) w.write(p.timestamp, p.pose);
    w.close();
}

namespace {

std::vector<io::TumPose> runOnMap(const graphslam::SlamEngine& engine) {
    std::vector<io::TumPose> out;
    for (TNodeID id = engine.mapNodes(); id < engine.nodes().size(); ++id) {
        if (engine.relocalizer().groupOf(id) != 0) continue;
        out.push_back({engine.nodes().at(id).timestamp, engine.graph().nodes.at(id)});
    }
    return out;
}
bool inGraph(const Graph& graph, const graphslam::LoopClosure& lc) {
    const auto range = graph.edges.equal_range({lc.from, lc.to});
    for (auto it = range.first; it != range.second; ++it) {
        if (it->second.mean == lc.constraint.mean) return true;
    }
    return false;
}

/** The translation block of a constraint's covariance (its information inverted whole, so the
 * block is the translation's marginal); NaN where the information is not positive definite. */
Eigen::Matrix3d translationCovariance(const graphslam::Constraint& c) {
    const Eigen::Matrix<double, 6, 6> information = c.cov_inv.asEigen();
    const Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt(information);
    if (llt.info() != Eigen::Success) return Eigen::Matrix3d::Constant(NAN);
    const Eigen::Matrix<double, 6, 6> covariance =
        llt.solve(Eigen::Matrix<double, 6, 6>::Identity());
    return covariance.topLeftCorner<3, 3>();
}
}  // namespace

std::vector<outputs::ClosureRow> closureRows(const graphslam::SlamEngine& engine) {
    std::vector<outputs::ClosureRow> rows;
    const auto& nodes = engine.nodes();
    for (const auto& p : engine.proposals()) {
        const auto& lc = p.closure;
        outputs::ClosureRow r;
        r.fromNode = static_cast<long long>(lc.from);
        r.toNode = static_cast<long long>(lc.to);
        r.fromTime = nodes.at(lc.from).timestamp;
        r.toTime = nodes.at(lc.to).timestamp;
        r.source = lc.source;
        r.matchId = lc.matchId;
        r.score = lc.score;
        r.strong = lc.strong;
        r.hypothesis = p.hypothesis;
        r.kept = inGraph(engine.graph(), lc);
        r.measured = lc.constraint.mean;
        r.translationCovariance = translationCovariance(lc.constraint);
        rows.push_back(std::move(r));
    }
    return rows;
}

std::vector<outputs::NodeRow> nodeRows(const NodeStore& nodes, const std::vector<float>& engineMs,
                                       TNodeID firstTimed) {
    std::vector<outputs::NodeRow> rows;
    rows.reserve(nodes.size());
    for (TNodeID id = 0; id < nodes.size(); ++id) {
        const auto& r = nodes.at(id);
        // (a loaded map's nodes were not made by this run: not timed)
        const bool timed = id >= firstTimed && id - firstTimed < engineMs.size();
        rows.push_back({static_cast<long long>(id), r.timestamp, r.segment, r.keyframe,
                        timed ? engineMs[id - firstTimed] : std::nan("")});
    }
    return rows;
}

namespace detail {

namespace {

namespace fs = std::filesystem;
using graphslam::JsonObject;
using outputs::RunFile;

// The field map's cell [m]: the magnetic matcher's resample step is 0.05 m and a map read by
// eye needs a few readings per cell at walking speed and 100 Hz.
constexpr double kFieldMapCell = 0.1;

/** report.json, written last and whole: a report.json there means every output was written. */
void writeReport(const JsonObject& report, const std::string& dir) {
    const std::string path = outputs::pathIn(dir, RunFile::Report);
    const std::string partial = path + ".partial";
    {
        std::ofstream json(partial);
        report.write(json);
        json << "\n";
        if (!json) throw std::runtime_error(partial + ": write failed");
    }
    fs::rename(partial, path);
}

}  // namespace

void writeOutputs(const RunInputs& in, const LoopOutcome& loop, const SlamRunOptions& options,
                  std::ostream& out, std::ostream& err, SlamRunResult& result) {
    const auto& engine = *in.engine;
    const std::string& dir = options.outDir;
    const auto path = [&](RunFile file) { return outputs::pathIn(dir, file); };
    const auto& graph = engine.graph();
    const auto& closures = engine.optimizer().loopClosures();
    result.nodes = graph.nodes.size();
    result.loopClosures = closures.size();
    // Every node, optimized; in a loaded map, the run's own nodes once they joined it (before,
    // a segment of its own: no pose in the map's frame to report).
    const auto trajectory = engine.mapNodes() > 0 ? runOnMap(engine) : nodeTrajectory(graph, engine.nodes());
    writeTrajectory(path(RunFile::Trajectory), trajectory);
    {
        Graph solved = graph;  // its odometry edges as the solves used them
        engine.optimizer().calibrateEdges(solved);
        solved.saveToTextFile(path(RunFile::Graph));
    }
    outputs::writeClosureTable(path(RunFile::Closures), closureRows(engine));
    outputs::writeNodeTable(path(RunFile::Nodes),
                            nodeRows(engine.nodes(), engine.stats().nodeMs, engine.mapNodes()));
    const auto& beforeKidnap = engine.relocalizer().mapAtFirstKidnap();
    if (!beforeKidnap.empty()) {
        // What the map was when the first kidnap began: lodestone-eval relocation compares
        // it with the end of the run (what relocations did to the map).
        io::TumTrajectoryWriter w(path(RunFile::MapAtFirstKidnap));
        for (const auto& [id, pose] : beforeKidnap) w.write(engine.nodes().at(id).timestamp, pose);
        w.close();
    }
    const std::size_t mapPoints = writeMapPly(path(RunFile::Map), graph, engine.nodes());
    cv::imwrite(path(RunFile::GraphPlot), plotGraph(graph, closures));
    if (!loop.magnetic.empty()) {
        eval::FieldMapBuilder fieldMap(trajectory, kFieldMapCell);
        for (const auto& r : loop.magnetic) {
            fieldMap.add(r.time, r.sensorOffset, r.magnitude, loop.magneticLabels[r.label]);
        }
        cv::imwrite(path(RunFile::FieldMap), fieldMap.render("|B| on the optimized trajectory"));
    }

    JsonObject report;
    report.set("tool", "lodestone-slam");
    JsonObject input;
    input.set(options.live ? "live" : options.scenario.empty() ? "rawlog" : "scenario",
              options.live ? options.live->name()
              : options.scenario.empty() ? options.rawlog : options.scenario)
        .set("config", options.config)
        .set("max_seconds", options.maxSeconds)
        .set("decode_ahead", options.decodeAhead)
        .set("decode_threads", in.decodeThreads);
    report.set("input", input);
    report.set("engine", engine.describe());
    report.set("timing", timingJson(engine.stats(), loop, in.prefetcher));
    report.set("map_points", mapPoints);

    const std::string gtPath = in.simulator ? path(RunFile::GroundTruth) : options.groundTruth;
    if (!gtPath.empty()) {
        const auto gt = io::readTumTrajectory(gtPath);
        const auto ate = eval::absoluteTrajectoryError(trajectory, gt);
        if (ate.pairs >= 3) {
            result.ateRmse = ate.rmse;
            report.set("ate", JsonObject()
                                  .set("ground_truth", gtPath)
                                  .set("pairs", ate.pairs)
                                  .set("rmse_m", ate.rmse)
                                  .set("mean_m", ate.mean)
                                  .set("median_m", ate.median)
                                  .set("max_m", ate.max));
            cv::imwrite(path(RunFile::TrajectoryPlot), eval::plotTrajectories(trajectory, gt, ate));
        } else {
            err << "lodestone-slam: warning: only " << ate.pairs << " nodes match " << gtPath
                << " in time; no ATE\n";
        }
    }
    if (options.mesh) report.set("mesh", writeMesh(in, loop, options, err));
    if (!options.mapOut.empty()) {
        report.set("map_out", saveMap(in, options, err, result)
                                  .set("saved_while_running", loop.mapsSaved));
    }
    if (!result.error.empty()) report.set("error", result.error);
    writeReport(report, dir);

    std::size_t rejected = 0;
    for (const auto& lc : closures) rejected += lc.rejected;
    const double wall = loop.wallSeconds;
    char line[256];
    std::snprintf(line, sizeof line,
                  "lodestone-slam: %zu nodes, %zu loop closures (%zu rejected), %zu frames, "
                  "%.1f s of data in %.1f s (%.2fx real time)\n",
                  result.nodes, result.loopClosures, rejected, engine.stats().frames,
                  loop.dataSeconds, wall, wall > 0 ? loop.dataSeconds / wall : 0.0);
    out << line;
    if (result.ateRmse) {
        std::snprintf(line, sizeof line, "ATE RMSE %.4f m over %zu nodes (ground truth %s)\n",
                      *result.ateRmse, trajectory.size(), gtPath.c_str());
        out << line;
    }
    // The files written, in the table's order.
    out << "outputs in " << fs::path(dir).string() << ":";
    for (const auto& file : outputs::runFiles()) {
        if (fs::exists(outputs::pathIn(dir, file.file))) out << " " << file.name;
    }
    out << "\n";
}

}  // namespace detail

}  // namespace lodestone::slamapp
