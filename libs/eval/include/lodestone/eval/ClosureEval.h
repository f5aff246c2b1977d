#pragma once

#include <lodestone/io/TumTrajectory.h>
#include <lodestone/outputs/ClosureTable.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace lodestone::eval {

/** One line of lodestone-slam's closures.csv (outputs::readClosureTable reads them). */
using ReportedClosure = outputs::ClosureRow;

struct ClosureEvalOptions {
    double radius{0.5};  ///< [m] a detection is right within this of the truth
    /** [rad] a revisit faces the same way as the earlier visit within this, or the opposite way
     * within this (a corridor walked back); in between it crosses and is not a pass. */
    double revisitYaw{45 * M_PI / 180};
    double minGap{5.0};         ///< [m] of true travel between a place and its revisit
    double minPassLength{1.0};  ///< [m] shorter revisits are not counted as passes
    double pieceLength{2.0};    ///< [m] longer revisits are cut into passes this long
    double maxDt{0.02};         ///< [s] timestamp association with the truth
    /** A closure is consistent when its error's squared Mahalanobis distance under its own
     * claimed covariance (the horizontal block) is within this: 2 dof, 99.73 %. */
    double ownRegionChi2{11.83};
};

/** Which way a revisit pass runs relative to the earlier visit it repeats. A node that repeats
 * an earlier place both ways (a corridor walked there, back, and there again) counts as Same:
 * a matcher that compares in travel order alone can find it. */
enum class PassDirection { Same = 0, Opposite = 1 };

/** One revisit pass: the run's nodes [first, last] (IDs). */
struct RevisitPass {
    std::size_t first{0}, last{0};
    PassDirection direction{PassDirection::Same};
};

/** The run's revisit passes as evaluateClosures counts them (`trajectory`: every node of the
 * run, in ID order). */
std::vector<RevisitPass> revisitPasses(const std::vector<io::TumPose>& trajectory,
                                       const std::vector<io::TumPose>& truth,
                                       const ClosureEvalOptions& options = {});

/** Revisit passes of one direction and how many a matcher found. */
struct PassRecall {
    std::size_t passes{0};
    std::size_t detected{0};  ///< with a right detection at any score
    std::size_t at100{0};     ///< with a right detection scoring above every wrong one
    double recall() const { return passes ? double(detected) / double(passes) : NAN; }
    double recallAt100() const { return passes ? double(at100) / double(passes) : NAN; }
};

/** One matcher's detection quality against the ground truth. */
struct MatcherQuality {
    std::string source;
    std::size_t proposals{0}, right{0}, wrong{0}, judged{0};
    std::size_t kept{0}, keptWrong{0};              ///< in the final graph
    std::size_t hypotheses{0}, hypothesesWrong{0};  ///< joined two groups (after kidnaps)
    double medianError{NAN}, maxError{NAN};  ///< [m] position error of the right ones ... all
    std::size_t passes{0};          ///< true revisit passes, both directions (every matcher)
    std::size_t passesDetected{0};  ///< with a right detection at any score
    std::size_t passesAt100{0};     ///< with a right detection scoring above every wrong one
    PassRecall byDirection[2];      ///< the same, by PassDirection
    std::vector<std::size_t> detectedPasses;  ///< their indices in revisitPasses(), ascending
    double threshold{NAN};                    ///< the highest wrong score (none wrong: NaN)
    /** Consistency: closures with a claimed covariance judged against it, those whose
     * horizontal error lies inside their own `ownRegionChi2` region, and of the wrong ones
     * (beyond `radius`) those inside it (a claim loose enough to cover them). */
    std::size_t covarianceJudged{0}, insideOwnRegion{0}, wrongInsideOwnRegion{0};
    double recall() const { return passes ? double(passesDetected) / double(passes) : NAN; }
    double recallAt100() const { return passes ? double(passesAt100) / double(passes) : NAN; }
    double precision() const { return judged ? double(right) / double(judged) : NAN; }
    double consistency() const {
        return covarianceJudged ? double(insideOwnRegion) / double(covarianceJudged) : NAN;
    }
};

/** A closure's horizontal error against the truth (`to` measured from `from` against the truth
 * of both, in the frame of `from`) as a squared Mahalanobis distance under the horizontal
 * block of the covariance it claims; NaN where it claims none or one not positive definite. */
double closureErrorChi2(const ReportedClosure& closure, const mrpt::poses::CPose3D& trueFrom,
                        const mrpt::poses::CPose3D& trueTo);

/** Judges every proposed closure against the truth: the measured pose of `to` composed on the
 * true pose of `from` must land within `radius` of the true pose of `to`. A revisit pass is a
 * run of consecutive nodes (`trajectory`: every node of the run, in ID order) each within
 * `radius` of the truth of a node at least `minGap` of true travel earlier,
 * `minPassLength` long or more, cut into passes of `pieceLength`; a matcher detects a pass when a
 * right closure ends inside it. Passes are told apart by direction (PassDirection): a node
 * within `revisitYaw` of the earlier node's heading runs the same way, within `revisitYaw` of
 * its reverse the opposite way. Recall at 100 % precision (the DBoW2 / FAB-MAP convention): passes
 * detected by right closures scoring above the highest-scoring wrong one, over all passes.
 * Consistency: each closure's error weighed by its own claimed covariance (closureErrorChi2). */
std::vector<MatcherQuality> evaluateClosures(const std::vector<ReportedClosure>& closures,
                                             const std::vector<io::TumPose>& trajectory,
                                             const std::vector<io::TumPose>& truth,
                                             const ClosureEvalOptions& options = {});

/** A markdown table, a row per matcher, and a line saying what the columns mean. */
std::string formatClosureQuality(const std::vector<MatcherQuality>& q,
                                 const ClosureEvalOptions& options);

}  // namespace lodestone::eval
