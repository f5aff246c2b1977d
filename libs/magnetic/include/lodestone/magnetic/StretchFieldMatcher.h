#pragma once

#include <lodestone/magnetic/PlanarFieldGrid.h>

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <vector>

namespace lodestone::magnetic {

/** One reading of a recent stretch of the path, placed relative to the stretch's anchor (its
 * newest pose): where and facing which way the robot read it, the reading in the levelled robot
 * frame, and how much it counts (readings closer than the field's length scale repeat each
 * other's errors: a reading every 5 cm of a 0.3 m length scale counts a sixth). */
struct StretchSample {
    Eigen::Vector3d pose{Eigen::Vector3d::Zero()};   ///< x, y [m], yaw [rad] in the anchor's frame
    Eigen::Vector3d field{Eigen::Vector3d::Zero()};  ///< [uT] levelled robot frame
    double weight{1.0};
};

struct StretchMatchParams {
    double passSigma{1.0};           ///< [uT] per component, beyond the map's variance and sigma_n
    double tailDof{4.0};             ///< Student-t residual (0: Gaussian), as FieldParticleFilter
    double maxOffset{1.0};           ///< [m] the position search's half-width, at most
    double maxYaw{30 * M_PI / 180};  ///< [rad] the heading search's half-width, at most
    double step{0.1};                ///< [m] the search grid's position step
    double yawStep{2 * M_PI / 180};  ///< [rad] its heading step
    double fineStep{0.05};           ///< [m] the refinement's steps, around the best cell
    double fineYawStep{0.5 * M_PI / 180};
};

/** Where a stretch of readings lies in a field map, near where the graph puts it: every anchor
 * pose on a grid within the prior's gate is scored by the stretch's readings against the map
 * (each a Student-t residual under the map's variance + sigma_n^2 + passSigma^2), as a log
 * likelihood ratio against the reading coming from a place of the map drawn at random (a mixture
 * over up to 128 of its cells: a calm reading matches a calm place anywhere, and the prior's
 * Gaussian would call that evidence; off the map's band a reading weighs nothing). The result is a
 * posterior over the grid (the prior a Gaussian in position, flat in heading), its moments refined
 * around its best cell, and the evidence that the stretch is somewhere on the map at all. */
struct StretchMatch {
    /** log of the Bayes factor: the stretch at one of the grid's poses (prior-weighted) against
     * its readings coming from anywhere on the map. */
    double logEvidence{-INFINITY};
    Eigen::Vector3d pose{Eigen::Vector3d::Zero()};  ///< the anchor in the map [m, m, rad]
    Eigen::Matrix3d covariance{Eigen::Matrix3d::Identity()};
    /** Posterior spread on the search grid (largest position sigma [m], heading sigma [rad]):
     * more than one place in it shows here. */
    double positionSigma{INFINITY}, yawSigma{INFINITY};
    double support{0};  ///< sum of the weights of the samples on the map's band at `pose`
    /** The residuals at `pose`: sum over the samples on the band of weight x r^2 / variance -
     * about chi-square with 3 x `support` degrees of freedom where the stretch is there. */
    double fit{0};
    std::size_t candidates{0};
};

StretchMatch matchStretch(const PlanarFieldGrid& map, const std::vector<StretchSample>& stretch,
                          const Eigen::Vector3d& priorPose, const Eigen::Matrix2d& priorCovariance,
                          const StretchMatchParams& p = {});

}  // namespace lodestone::magnetic
