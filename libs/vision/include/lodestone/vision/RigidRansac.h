#pragma once

#include <mrpt/config/CLoadableOptions.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace lodestone::config {
class IniSection;
}

namespace lodestone::vision {

/** The rigid motion aligning two matched 3D point sets: dst_i ≈ R src_i + t (paper 001:
 * p_i = R p'_i + t, solved by SVD of W = sum q_i q'_i^T after removing the centroids; Eigen's
 * umeyama does exactly that, with the reflection fix). */
struct RigidEstimate {
    bool success{false};
    Eigen::Isometry3d transform{Eigen::Isometry3d::Identity()};  ///< src -> dst
    std::vector<int> inliers;                                    ///< indices into the input pairs
    double rmse{0};                                              ///< over the inliers [m]
    /** 6x6 covariance of a left perturbation exp(xi) * transform, xi = (rx, ry, rz, tx, ty, tz)
     * [rad, m], from the inlier residuals: sigma^2 (J^T J)^-1. */
    Eigen::Matrix<double, 6, 6> covariance{Eigen::Matrix<double, 6, 6>::Identity()};
};

/** SVD alignment of all given pairs (no outlier handling). Needs >= 3 non-collinear pairs. */
Eigen::Isometry3d alignRigid(const Eigen::Matrix3Xd& src, const Eigen::Matrix3Xd& dst);

/** The same with a weight per pair (weighted least squares: weighted centroids and
 * W = sum w_i q'_i q_i^T, reflection fixed). */
Eigen::Isometry3d alignRigidWeighted(const Eigen::Matrix3Xd& src, const Eigen::Matrix3Xd& dst,
                                     const Eigen::VectorXd& weights);

/** RANSAC over minimal 3-pair samples, then a refit on all inliers weighted by their expected
 * noise (sigma = pointNoise + depthNoise z^2 in each point; structured-light depth), and a final
 * inlier pass.
 * A pair is an inlier when |R src + t - dst| < threshold + depthScale * z_dst^2 (depth noise of
 * structured light grows with z^2). Deterministic for a given seed. */
class RigidRansac {
  public:
    struct Params : public mrpt::config::CLoadableOptions {
        int iterations{200};          ///< RANSAC hypotheses
        double threshold{0.03};       ///< inlier distance at zero depth [m]
        double depthScale{0.006};     ///< added inlier distance per z^2 [1/m]
        int minInliers{15};           ///< fewer: no estimate
        double minInlierRatio{0.25};  ///< inliers / pairs below this: no estimate
        double pointNoise{0.01};      ///< 3D point noise at zero depth, for the weights [m]
        double depthNoise{1.425e-3};  ///< its growth with depth: + depthNoise z^2 [1/m]
        /** Adaptive stop: end once an all-inlier sample has been drawn with this probability,
         * given the best inlier ratio so far (e.g. 0.999); 0: always `iterations`. */
        double confidence{0};

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                const std::string& section) override;
        /** Reads this part's keys from a section shared with others (which checks strangers). */
        void read(config::IniSection& section);
        void dumpToTextStream(std::ostream& out) const override;
    };

    RigidRansac();
    explicit RigidRansac(const Params& params);
    RigidEstimate estimate(const Eigen::Matrix3Xd& src, const Eigen::Matrix3Xd& dst,
                           std::uint64_t seed = 1) const;
    const Params& params() const { return params_; }

  private:
    std::vector<int> inliersOf(const Eigen::Isometry3d& T, const Eigen::Matrix3Xd& src,
                               const Eigen::Matrix3Xd& dst) const;
    Params params_;
};

}  // namespace lodestone::vision
