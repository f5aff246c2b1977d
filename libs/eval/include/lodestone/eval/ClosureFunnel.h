#pragma once

#include <lodestone/eval/ClosureEval.h>

#include <map>
#include <string>
#include <vector>

namespace lodestone::eval {

/** A loop closer's recall funnel, as lodestone-slam's report.json holds it when the run had
 * ground truth (`truth_funnel`: per query that truly revisits a place, the stage that place
 * reached), joined with the run's revisit passes: every pass the closer missed, by the furthest
 * stage any query inside it reached. */
struct ClosureFunnel {
    std::string decider;                  ///< its class name (closures.csv's source)
    std::vector<std::string> stageNames;  ///< by stage number
    /** Missed passes by furthest stage (-1: no query inside the pass), per PassDirection. */
    std::map<int, std::size_t> missedBy[2];
    std::size_t passes{0}, missed{0};
    double truthInsideGate{NAN};  ///< share of queries whose true place lay inside its gate
};

/** The funnels in `reportPath` (every edge decider with one), joined with `passes`
 * (revisitPasses) and what each decider detected (`qualities`: evaluateClosures on the same
 * run; a decider without a row detected nothing). Throws std::runtime_error naming the file
 * when it cannot be read. */
std::vector<ClosureFunnel> readClosureFunnels(const std::string& reportPath,
                                              const std::vector<RevisitPass>& passes,
                                              const std::vector<MatcherQuality>& qualities);

/** "stage same / opposite, ..." over the stages with a missed pass ("none" when none was). */
std::string missedByStage(const ClosureFunnel& funnel);

/** A markdown table, a row per decider: passes missed by stage (same / opposite direction). */
std::string formatClosureFunnels(const std::vector<ClosureFunnel>& funnels);

}  // namespace lodestone::eval
