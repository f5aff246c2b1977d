#pragma once

#include <lodestone/eval/TrajectoryError.h>
#include <lodestone/outputs/NodeTable.h>

#include <string>
#include <vector>

namespace lodestone::eval {

/** One segment of a run (the nodes between two VO losses or kidnaps that nothing bridged),
 * aligned with the truth on its own. */
struct SegmentError {
    int segment{0};
    AteResult ate;
};

/** A run judged whole and piece by piece: where a run's segments never joined, the whole
 * run's ATE mostly says where the unjoined pieces were left; each segment aligned on its own
 * says how well the odometry and closures tracked within it. */
struct SegmentEvaluation {
    AteResult whole;
    std::vector<SegmentError> segments;  ///< those with at least 3 poses matched to the truth
    double pooledRmse{0};                ///< over every segment's pairs, each on its own [m]
    std::size_t pooledPairs{0};
    bool gapsReported{false};            ///< the run's report held VO gaps (an RGB-D node decider)
    std::vector<double> gapSeconds;      ///< each VO gap's length [s]
};

/** `nodes` says each trajectory pose's segment (by timestamp, nodes.csv). */
SegmentEvaluation evaluateSegments(const std::vector<outputs::NodeRow>& nodes,
                                   const std::vector<io::TumPose>& trajectory,
                                   const std::vector<io::TumPose>& truth, double maxDt = 0.02);

/** The VO gaps a run's report.json holds (its node decider's `vo_gap_seconds`); false when it
 * holds none (a decider without VO). Throws naming the file when it cannot be read. */
bool readVoGaps(const std::string& reportJson, std::vector<double>& gapSeconds);

/** A few lines: the whole run's ATE, the VO gaps, each segment's ATE on its own and pooled. */
std::string formatSegmentEvaluation(const SegmentEvaluation& evaluation);

}  // namespace lodestone::eval
