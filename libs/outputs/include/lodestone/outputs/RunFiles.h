#pragma once

#include <string>
#include <vector>

namespace lodestone::outputs {

/** Every file a lodestone-slam run writes in its output folder. */
enum class RunFile {
    Trajectory,
    Graph,
    Closures,
    Nodes,
    Map,
    Report,
    GraphPlot,
    TrajectoryPlot,
    GroundTruth,
    Events,
    MapAtFirstKidnap,
    FieldMap,
    Mesh,
};

/** One row of the table of a run's files: its name in the folder, its format and what it holds. */
struct RunFileSpec {
    RunFile file;
    const char* name;
    const char* format;
    const char* holds;
};

/** The table, in the order lodestone-slam lists what it wrote. The one place the names live:
 * the SLAM run writes through it, lodestone-eval and lodestone-inspect read through it. */
const std::vector<RunFileSpec>& runFiles();

/** The file's name in a run's folder ("closures.csv"). */
const char* fileName(RunFile file);

/** `dir/name` of the file. */
std::string pathIn(const std::string& dir, RunFile file);

}  // namespace lodestone::outputs
