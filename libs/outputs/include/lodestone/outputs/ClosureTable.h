#pragma once

#include <mrpt/poses/CPose3D.h>

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace lodestone::outputs {

/** One line of closures.csv: a loop closure a matcher proposed, as the engine recorded it. */
struct ClosureRow {
    long long fromNode{0}, toNode{0};
    double fromTime{0}, toTime{0};
    std::string source;        ///< the loop closer's class name
    std::size_t matchId{0};    ///< the closer's own id of the match (its logs, its funnel)
    double score{0};           ///< the closer's score (ORB inliers, minus a magnetic fit's RMS)
    bool strong{false};        ///< the closer's own verification passed
    bool hypothesis{false};    ///< a relocation hypothesis (across a kidnap)
    bool kept{false};          ///< an edge of the final graph
    mrpt::poses::CPose3D measured;  ///< `to` in the frame of `from`
    /** The covariance the closer claimed for `measured`'s translation (in the frame of
     * `from`; its information's 6 x 6 inverse, the translation block): what a judge of the
     * closure against the truth weighs its error by. NaN where a log predates it. */
    Eigen::Matrix3d translationCovariance{Eigen::Matrix3d::Constant(NAN)};
};

/** Writes closures.csv (a header, then a line per row). Throws naming the file on failure. */
void writeClosureTable(const std::string& path, const std::vector<ClosureRow>& rows);

/** Reads closures.csv (also a log written before the covariance columns: NaN there); throws
 * std::runtime_error naming the file and line when malformed. */
std::vector<ClosureRow> readClosureTable(const std::string& path);

}  // namespace lodestone::outputs
