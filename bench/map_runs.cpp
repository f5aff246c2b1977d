#include "map_runs.h"

#include <lodestone/eval/TrajectoryError.h>
#include <lodestone/graphslam/PoseGraph.h>
#include <lodestone/io/TumTrajectory.h>
#include <mrpt/math/CMatrixFixed.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <unordered_map>

#include "bench_reports.h"

using namespace lodestone;

mrpt::poses::CPose3D mapFrame(const std::string& mapRunOut, const std::string& mapRunTruth,
                              double& mapAte) {
    const auto ate = eval::absoluteTrajectoryError(
        io::readTumTrajectory(mapRunOut + "/trajectory.tum"), io::readTumTrajectory(mapRunTruth));
    mapAte = ate.rmse;
    return mrpt::poses::CPose3D(mrpt::math::CMatrixDouble44(ate.alignment.matrix()));
}

Coverage nearPath(const std::vector<Eigen::Vector2d>& path, double radius) {
    // Buckets of `radius`: a query looks at its own and the eight around it.
    const auto cell = [radius](double v) {
        return static_cast<std::int64_t>(std::floor(v / radius));
    };
    const auto key = [](std::int64_t ix, std::int64_t iy) {
        return (static_cast<std::uint64_t>(ix) << 32) ^ static_cast<std::uint32_t>(iy);
    };
    auto buckets =
        std::make_shared<std::unordered_map<std::uint64_t, std::vector<Eigen::Vector2d>>>();
    for (const auto& p : path) (*buckets)[key(cell(p.x()), cell(p.y()))].push_back(p);
    return [buckets, radius, cell, key](double x, double y) {
        const std::int64_t ix = cell(x), iy = cell(y);
        for (std::int64_t dx = -1; dx <= 1; ++dx)
            for (std::int64_t dy = -1; dy <= 1; ++dy) {
                const auto it = buckets->find(key(ix + dx, iy + dy));
                if (it == buckets->end()) continue;
                for (const auto& p : it->second)
                    if ((p - Eigen::Vector2d(x, y)).squaredNorm() <= radius * radius) return true;
            }
        return false;
    };
}

MapRunJudgement judgeMapRun(const std::string& out, const std::string& truthPath,
                            const maps::SavedMap& loaded, const mrpt::poses::CPose3D& T_world_map,
                            double near, const Coverage& covered) {
    MapRunJudgement j;
    const auto truth = io::readTumTrajectory(truthPath);
    // (the first kidnap record: the run's start in the map)
    const std::string all = slurp(out + "/report.json");
    const std::string report = all.substr(std::min(all.size(), all.find("\"kidnaps\"")));
    j.relocated = report.find("\"relocated\": true") != std::string::npos;
    j.travel = numberIn(report, "travel_to_relocation_m");
    if (j.relocated) {
        const mrpt::poses::CPose3D at(numberIn(report, "x"), numberIn(report, "y"), 0,
                                      numberIn(report, "yaw"), 0, 0);
        j.relocatedPose = at;
        j.relocationTime = numberIn(report, "relocation_time");
        if (const auto* t = eval::truthAt(truth, j.relocationTime, 0.05)) {
            const auto e = (-t->pose) + (T_world_map + at);
            j.errorXY = std::hypot(e.x(), e.y());
            j.errorYawDeg = std::abs(e.yaw()) * 180 / M_PI;
        }
    }
    // The run's nodes on the map, in the map's frame, against the truth: no alignment.
    const auto onMap = io::readTumTrajectory(out + "/trajectory.tum");
    double sum = 0;
    std::size_t judged = 0, pairs = 0, close = 0, inside = 0, closeInside = 0;
    for (const auto& p : onMap) {
        const auto* t = eval::truthAt(truth, p.timestamp, 0.05);
        if (!t) continue;
        const auto world = T_world_map + p.pose;
        const double d2 =
            std::pow(world.x() - t->pose.x(), 2) + std::pow(world.y() - t->pose.y(), 2);
        sum += d2;
        ++judged;
        // The share within `near`: the poses after the first relocation (before it the run's
        // nodes are placed only by the odometry back from there).
        if (!(p.timestamp >= j.relocationTime)) continue;
        close += d2 <= near * near;
        ++pairs;
        if (covered && covered(t->pose.x(), t->pose.y())) {
            ++inside;
            closeInside += d2 <= near * near;
        }
    }
    if (covered && pairs) {
        j.coveredShare = double(inside) / double(pairs);
        if (inside) j.withinCovered = double(closeInside) / double(inside);
        if (pairs > inside)
            j.withinUncovered = double(close - closeInside) / double(pairs - inside);
    }
    j.onMap = onMap.size();
    if (judged) j.ate = std::sqrt(sum / double(judged));
    if (pairs) j.within = double(close) / double(pairs);
    // The loaded map's nodes: where the run left them (graph.graph) against where they were.
    graphslam::Graph after;
    after.loadFromTextFile(out + "/graph.graph");
    for (const auto& [id, pose] : loaded.graph.nodes) {
        const auto& a = after.nodes.at(id);
        j.moved = std::max(j.moved, std::hypot(a.x() - pose.x(), a.y() - pose.y()));
    }
    return j;
}
