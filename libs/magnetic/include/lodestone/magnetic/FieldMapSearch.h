#pragma once

#include <lodestone/magnetic/GaussianProcess2D.h>
#include <lodestone/magnetic/PlanarAlignment.h>

#include <Eigen/Core>
#include <cstddef>
#include <string>

namespace lodestone::magnetic {

/** A stretch of readings placed against a field map over the plane (a 2-D GP of every earlier
 * reading near it) without a sequence match to start from: where the robot walks beside earlier
 * passes, the field it reads is not the one any earlier pass read, so the 1-D sequence matcher
 * finds nothing, but the map still predicts it.
 *
 * Translations of the stretch on a grid inside the pose gate are scored by the map's mean; the
 * best local optima are refined in the plane (PlanarAlignment) and judged by the joint
 * likelihood of the readings given the map (their correlation included). The match must explain
 * the readings better than the map's prior alone - the null: "the map knows nothing of this" -
 * by `minLogRatio`. Optima the likelihood cannot tell apart (one straight earlier pass predicts
 * the same field on either side of it) are kept together: the result is their likelihood- and
 * gate-weighted mixture, moment-matched, so what stays undecided shows as a loose direction of
 * the covariance instead of a coin toss. */
struct FieldMapSearchParams {
    double gridStep{0.1};     ///< [m] translations tried
    double maxRadius{1.5};    ///< [m] the searched region's cap, whatever the gate
    double gateChi2{11.83};   ///< the region: this chi-square (2 dof) of the gate covariance
    std::size_t refined{4};   ///< the best local optima refined in the plane
    double minLogRatio{10.0}; ///< over the null
    double maxNormalizedRms{2.0};
    /** [m] a result looser than this (largest position sigma) says nothing the gate did not. */
    double maxSigma{0.5};
    PlanarAlignmentParams plane;
};

enum class FieldMapVerdict { Accepted, NoFit, NotAboveNull, TooLoose };
std::string toString(FieldMapVerdict v);

struct FieldMapMatch {
    FieldMapVerdict verdict{FieldMapVerdict::NoFit};
    /** The move from where the points started (pivot: their centroid), its covariance the
     * mixture's. */
    PlanarAlignmentResult alignment;
    double logLikelihood{0};      ///< joint, of the best optimum
    double nullLogLikelihood{0};  ///< the same readings under the map's prior alone
    std::size_t hypotheses{0}, optima{0};
    bool accepted() const { return verdict == FieldMapVerdict::Accepted; }
};

/** `points` (m x 2): the stretch's reading positions where the graph has them; `query` (m x
 * channels) its readings; `gateCovariance`: how far off those positions can be (map frame). */
FieldMapMatch searchFieldMap(const GaussianProcess2D& map, const Eigen::MatrixX2d& points,
                             const Eigen::MatrixXd& query, const Eigen::Matrix2d& gateCovariance,
                             const FieldMapSearchParams& params);

}  // namespace lodestone::magnetic
