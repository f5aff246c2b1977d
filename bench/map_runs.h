// A run started in a saved map, judged against its truth in the map's frame with no
// re-alignment (bench_maps: simulated scenarios; bench_aalto_maps: Aalto's trials). The map's
// frame is tied to the world once, by the map run's own nodes aligned to its truth.
#pragma once

#include <lodestone/maps/SavedMap.h>
#include <mrpt/poses/CPose3D.h>

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

/** The map's frame in the world: the map run's trajectory (OUT/trajectory.tum) aligned to its
 * truth; `mapAte` its ATE. */
mrpt::poses::CPose3D mapFrame(const std::string& mapRunOut, const std::string& mapRunTruth,
                              double& mapAte);

struct MapRunJudgement {
    bool relocated{false};
    double travel{NAN};                     ///< [m] to the first relocation
    double relocationTime{NAN};             ///< [s]
    mrpt::poses::CPose3D relocatedPose;     ///< in the map's frame
    double errorXY{NAN}, errorYawDeg{NAN};  ///< of the relocated pose [m, deg]
    double ate{NAN};                        ///< the run's nodes on the map, map frame [m]
    double within{NAN};  ///< share of them after the first relocation within `near` of the truth
    std::size_t onMap{0};                   ///< the run's nodes on the map (trajectory.tum)
    /** Split by whether the map holds the place (the `covered` predicate): the share of the
     * run's nodes whose truth is covered, and `within` over those and over the rest. */
    double coveredShare{NAN}, withinCovered{NAN}, withinUncovered{NAN};
    double moved{0};  ///< [m] how far the loaded map's nodes moved
};

/** Whether the map holds the place (x, y) of the world: e.g. the map run passed near it. */
using Coverage = std::function<bool(double x, double y)>;

/** Covered: within `radius` of a point of `path` (world frame) - where a map run passed. */
Coverage nearPath(const std::vector<Eigen::Vector2d>& path, double radius);

/** The run whose outputs are in `out` (report.json, trajectory.tum, graph.graph), started in
 * `loaded`, against the truth `truthPath`; `covered` (optional) splits `within`. */
MapRunJudgement judgeMapRun(const std::string& out, const std::string& truthPath,
                            const lodestone::maps::SavedMap& loaded,
                            const mrpt::poses::CPose3D& T_world_map, double near = 0.3,
                            const Coverage& covered = {});
