#pragma once

#include <lodestone/magnetic/GaussianProcess2D.h>

#include <Eigen/Core>

namespace lodestone::magnetic {

/** The GP correction taken to the plane: where paper 000 eq. (3) slides the query along the
 * target's path, this moves the query stretch rigidly in the plane (dx, dy, dyaw about its
 * centroid) to maximize the fit of its readings to a 2-D GP of the target's field (Gauss-Newton
 * on the readings' residuals over the GP's predictive mean, with a weak prior holding the
 * start). It recovers where a revisit passed beside the earlier passes, which sliding along one
 * path cannot. */
struct PlanarAlignmentParams {
    double priorSigmaXY{0.3};   ///< [m] prior on the move either way
    double priorSigmaYaw{0.15}; ///< [rad]
    double maxShift{0.5};       ///< [m] a larger move is no alignment
    int iterations{30};
    double minSigma{0.01};      ///< [m] floor on the reported position sigmas
};

struct PlanarAlignmentResult {
    bool valid{false};
    Eigen::Vector3d delta{Eigen::Vector3d::Zero()};  ///< dx, dy [m], dyaw [rad]
    Eigen::Matrix3d covariance{Eigen::Matrix3d::Identity()};
    Eigen::Vector2d pivot{Eigen::Vector2d::Zero()};  ///< the query's centroid: dyaw turns about it
    double normalizedRms{0};  ///< residual RMS in predictive sigmas at the optimum
    double normalizedRmsStart{0};

    /** Where a query point at `p` lands after the move. */
    Eigen::Vector2d apply(const Eigen::Vector2d& p) const;
};

/** `gp` is fitted on the target's readings at their plane positions; `points` (m x 2) are the
 * query readings' positions in the same frame at the start, `query` their readings. */
PlanarAlignmentResult alignInPlane(const GaussianProcess2D& gp, const Eigen::MatrixX2d& points,
                                   const Eigen::MatrixXd& query, const PlanarAlignmentParams& params);

}  // namespace lodestone::magnetic
