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
 * Translations of the stretch on a grid inside the pose gate are scored by the map's predictive
 * density (mean and variance); the best local optima are refined (pattern search on the same
 * density, the heading free within twice the plane prior's sigma) and judged by the joint
 * likelihood of the readings given the map (their correlation included). The match must
 * explain the readings better than the map's prior alone - the null: "the map knows nothing of
 * this" - by a log Bayes factor of `minLogRatio`, the search's Occam factor included (the best
 * of hundreds of places tried fits an unrelated field well now and then); a look-alike place
 * elsewhere in the gate must fit clearly worse; and a best fit that still improves past the
 * gate's edge gives no verdict (the place may lie outside). Optima the likelihood cannot tell
 * apart within one place (one straight earlier pass predicts the same field on either side of
 * it) are kept together: the result is their likelihood- and gate-weighted mixture,
 * moment-matched, so what stays undecided shows as a loose direction of the covariance instead
 * of a coin toss. */
struct FieldMapSearchParams {
    double gridStep{0.1};     ///< [m] translations tried
    double maxRadius{2.5};    ///< [m] the widest gate searched (the cost grows with its area)
    double gateChi2{11.83};   ///< the region: this chi-square (2 dof) of the gate covariance
    std::size_t refined{4};   ///< the best local optima refined in the plane
    double minLogRatio{10.0}; ///< log Bayes factor over the null
    double maxNormalizedRms{2.0};
    /** [m] a result looser than this (largest position sigma) says nothing the gate did not. */
    double maxSigma{0.5};
    /** [m] optima farther apart than this are different places: the likelier must win by
     * `ambiguityLogRatio` on the readings alone (not helped by the gate), else neither does -
     * the sequence matcher's rule for look-alike places. Nearer optima are one place, mixed. */
    double distinctRadius{1.5};
    double ambiguityLogRatio{10.0};
    PlanarAlignmentParams plane;
};

/** GateTooWide: the gate reaches beyond `maxRadius`: what lies outside the searched region
 * could fit as well, so no search is made. */
enum class FieldMapVerdict { Accepted, NoFit, NotAboveNull, Ambiguous, TooLoose, GateTooWide };
std::string toString(FieldMapVerdict v);

struct FieldMapMatch {
    FieldMapVerdict verdict{FieldMapVerdict::NoFit};
    /** The move from where the points started (pivot: their centroid), its covariance the
     * mixture's. */
    PlanarAlignmentResult alignment;
    double logLikelihood{0};      ///< joint, of the best optimum
    double nullLogLikelihood{0};  ///< the same readings under the map's prior alone
    /** log Bayes factor of a match against the null: the (dispersion-deflated) ratio of the
     * two, with the Occam factor of the search (the posterior's area over the region's). */
    double logEvidence{0};
    std::size_t hypotheses{0}, optima{0};
    bool accepted() const { return verdict == FieldMapVerdict::Accepted; }
};

/** How far the gate reaches: the chi-square ellipse's largest semi-axis [m]. */
double gateRadius(const Eigen::Matrix2d& gateCovariance, double gateChi2);

/** `points` (m x 2): the stretch's reading positions where the graph has them; `query` (m x
 * channels) its readings; `gateCovariance`: how far off those positions can be (map frame). */
FieldMapMatch searchFieldMap(const GaussianProcess2D& map, const Eigen::MatrixX2d& points,
                             const Eigen::MatrixXd& query, const Eigen::Matrix2d& gateCovariance,
                             const FieldMapSearchParams& params);

}  // namespace lodestone::magnetic
