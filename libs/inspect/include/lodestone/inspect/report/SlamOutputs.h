#pragma once

#include <lodestone/eval/ClosureEval.h>
#include <lodestone/eval/RelocationEval.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/outputs/NodeTable.h>

#include <optional>
#include <string>
#include <vector>

namespace lodestone::inspect::report {

/** One line of lodestone-slam's nodes.csv (outputs::readNodeTable reads them). */
using NodeRow = outputs::NodeRow;

/** What a lodestone-slam output folder holds, for the report. Only trajectory.tum is needed;
 * what else is missing is listed in `missing` and its section left out. */
struct SlamOutputs {
    std::string dir;
    std::vector<io::TumPose> trajectory;          ///< trajectory.tum: every node, optimized
    std::vector<eval::ReportedClosure> closures;  ///< closures.csv: every proposal
    std::vector<NodeRow> nodes;                   ///< nodes.csv
    std::vector<eval::ReportedKidnap> kidnaps;    ///< report.json's relocalization records
    std::vector<io::TumPose> groundTruth;         ///< --ground-truth, or DIR/ground_truth.tum
    std::string groundTruthPath;
    /** report.json's headline figures, as "name: value" lines (nodes, closures, ATE, rate). */
    std::vector<std::pair<std::string, std::string>> facts;
    std::vector<std::string> missing;  ///< files absent or unreadable, with why
};

/** Reads `dir` (a lodestone-slam --out folder). Throws std::runtime_error naming the file when
 * trajectory.tum is absent or malformed, or a ground truth given explicitly cannot be read. */
SlamOutputs readSlamOutputs(const std::string& dir, const std::string& groundTruth = "");

}  // namespace lodestone::inspect::report
