#include <lodestone/outputs/RunFiles.h>

#include <filesystem>
#include <stdexcept>

namespace lodestone::outputs {

const std::vector<RunFileSpec>& runFiles() {
    static const std::vector<RunFileSpec> table = {
        {RunFile::Trajectory, "trajectory.tum", "TUM", "every node's optimized pose"},
        {RunFile::Graph, "graph.graph", "MRPT graph text", "the pose graph, loadable by graph-slam"},
        {RunFile::Closures, "closures.csv", "CSV (ClosureTable)",
         "every closure a loop closer proposed: its score, the covariance it claimed, whether "
         "the graph kept it"},
        {RunFile::Nodes, "nodes.csv", "CSV (NodeTable)",
         "per node: time, segment, keyframe, engine time"},
        {RunFile::Map, "map.ply", "binary PLY", "coloured keyframe clouds on the optimized poses"},
        {RunFile::Report, "report.json", "JSON",
         "parameters, counts, timings, ATE, relocation records; written last"},
        {RunFile::GraphPlot, "graph.png", "PNG", "nodes and loop closures"},
        {RunFile::TrajectoryPlot, "trajectory.png", "PNG", "the trajectory against the truth"},
        {RunFile::GroundTruth, "ground_truth.tum", "TUM", "the simulator's truth (--sim)"},
        {RunFile::Events, "events.txt", "KidnapEvents", "the simulator's kidnaps (--sim)"},
        {RunFile::MapAtFirstKidnap, "map_at_first_kidnap.tum", "TUM",
         "the map's nodes as they were when the first kidnap began"},
        {RunFile::FieldMap, "field_map.png", "PNG",
         "|B| of every magnetometer reading on the optimized trajectory"},
        {RunFile::Mesh, "mesh.ply", "binary PLY",
         "the dense model: keyframes fused along the optimized poses, meshed (--mesh)"},
    };
    return table;
}

const char* fileName(RunFile file) {
    for (const auto& spec : runFiles()) {
        if (spec.file == file) return spec.name;
    }
    throw std::logic_error("outputs::fileName: a RunFile missing from the table");
}

std::string pathIn(const std::string& dir, RunFile file) {
    return (std::filesystem::path(dir) / fileName(file)).string();
}

}  // namespace lodestone::outputs
