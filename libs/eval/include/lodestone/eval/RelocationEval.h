#pragma once

#include <lodestone/io/KidnapEvents.h>
#include <lodestone/io/TumTrajectory.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace lodestone::eval {

/** What lodestone-slam's report.json says of one kidnap (engine.relocalization.kidnaps). */
struct ReportedKidnap {
    int segment{0};
    long long firstNode{-1};  ///< node ID (= line of trajectory.tum) opening the segment
    double liftTime{NAN}, putDownTime{NAN};
    bool relocated{false};
    /** Merged into the map only after the segment ended (not relocated while in it). */
    bool mergedLate{false};
    double mergeTime{NAN};
    double relocationTime{NAN}, travel{NAN};
    double x{0}, y{0}, yaw{0};  ///< relocated pose, map frame
    std::string deciders;
};

/** Reads `engine.relocalization.kidnaps` of a lodestone-slam report.json. Throws
 * std::runtime_error naming the file (and the key) when it is not such a report. */
std::vector<ReportedKidnap> readReportedKidnaps(const std::string& reportJson);

/** One kidnap judged against the ground truth. */
struct RelocationVerdict {
    int index{0};              ///< the events file's
    bool detected{false};      ///< a segment of the run started with this kidnap
    bool relocated{false};
    bool mergedLate{false};           ///< the segment joined the map only after it ended
    double secondsToMerge{NAN};       ///< then: from the true put-down to that merge
    double secondsToRelocation{NAN};  ///< from the true put-down
    double travelToRelocation{NAN};   ///< [m] the segment's odometry
    double positionError{NAN};        ///< [m] relocated pose vs truth, the map aligned on its
    double yawError{NAN};             ///< [rad] ... pre-kidnap nodes as they were at the lift
    bool wrong{false};                ///< error > `wrongDistance` or > `wrongYaw`
    std::string deciders;
};

struct RelocationEvaluation {
    std::vector<RelocationVerdict> kidnaps;
    std::size_t falseDetections{0};  ///< segments no true kidnap explains
    /** ATE of the nodes mapped before the first lift: as they were then, and at the end. */
    std::optional<double> mapAteBefore, mapAteAfter;
    std::optional<double> runAte;  ///< every node of the final trajectory
};

struct RelocationEvalOptions {
    double wrongDistance{0.5};      ///< [m]
    double wrongYaw{10 * M_PI / 180};  ///< [rad]
    double matchTolerance{1.0};     ///< [s] a segment's lift (or first node) vs a true kidnap
    double maxDt{0.02};             ///< [s] timestamp association
};

/** `trajectory`: the run's final node poses; `mapBefore`: the map at the first lift (may be
 * empty: no map damage then); `truth`: ground truth; `events`: the true kidnaps. */
RelocationEvaluation evaluateRelocations(const std::vector<ReportedKidnap>& reported,
                                         const std::vector<io::TumPose>& trajectory,
                                         const std::vector<io::TumPose>& mapBefore,
                                         const std::vector<io::TumPose>& truth,
                                         const std::vector<io::KidnapEventRecord>& events,
                                         const RelocationEvalOptions& options = {});

/** The per-kidnap table (markdown) and the summary lines. */
std::string formatRelocationEvaluation(const RelocationEvaluation& e);

}  // namespace lodestone::eval
