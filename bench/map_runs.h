// A run started in a saved map, judged against its truth in the map's frame with no
// re-alignment (bench_maps: simulated scenarios; bench_aalto_maps: Aalto's trials). The map's
// frame is tied to the world once, by the map run's own nodes aligned to its truth.
#pragma once

#include <lodestone/maps/SavedMap.h>
#include <mrpt/poses/CPose3D.h>

#include <cstddef>
#include <string>

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
    double within{NAN};                     ///< share of them within `near` of the truth
    std::size_t onMap{0};                   ///< the run's nodes on the map (trajectory.tum)
    double moved{0};                        ///< [m] how far the loaded map's nodes moved
};

/** The run whose outputs are in `out` (report.json, trajectory.tum, graph.graph), started in
 * `loaded`, against the truth `truthPath`. */
MapRunJudgement judgeMapRun(const std::string& out, const std::string& truthPath,
                            const lodestone::maps::SavedMap& loaded,
                            const mrpt::poses::CPose3D& T_world_map, double near = 0.3);
