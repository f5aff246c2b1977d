#pragma once

#include <lodestone/vision/OrbFeatures.h>
#include <lodestone/vision/RgbdFrame.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <vector>

namespace lodestone::vision {

/** A prediction of where the current frame is, from another sensor (the wheels): the current
 * optical frame's pose in the reference's, and the covariance of a left perturbation
 * exp(xi) T_ref_cur, xi = (w, v) rotation first (as RigidEstimate's). */
struct MotionPrior {
    Eigen::Isometry3d T_ref_cur{Eigen::Isometry3d::Identity()};
    Eigen::Matrix<double, 6, 6> covariance{Eigen::Matrix<double, 6, 6>::Identity()};
};

/** Descriptor matching restricted by a motion prior (ORB-SLAM's motion-model tracking): each
 * reference feature's 3D point is projected into the current image through the prior, and only
 * current keypoints inside its chi-square gate are compared with it. The gate's 2x2 covariance
 * is propagated, not chosen: the prior's covariance and the reference point's own noise
 * (RigidRansac's model: sigma = pointNoise + depthNoise z^2) through the projection's Jacobian,
 * plus the keypoint's detection noise at its pyramid level. Within the gates the rules are the
 * brute-force matcher's: best Hamming distance under a gate, ratio test against the gate's
 * second best, and a cross-check (the current keypoint's best among the reference features
 * whose gates hold it). Keypoints are bucketed in a grid so a gate costs only its cells. */
class GuidedMatcher {
  public:
    struct Params {
        double gateChi2{11.83};     ///< chi-square gate, 2 dof (11.83: 99.73 %, "3 sigma")
        double keypointSigma{1.0};  ///< ORB keypoint position noise at level 0 [px]
        double scaleFactor{1.2};    ///< ORB's pyramid step: the noise grows with the level
        double pointNoise{0.01};    ///< reference point noise at zero depth [m]
        double depthNoise{1.425e-3};  ///< ... growing by this times z^2 [1/m]
        int maxDistance{64};          ///< Hamming gate [bits]
        double ratio{0.0};            ///< best / second best in the gate below this; 0: off
        bool crossCheck{true};
        int cellSize{16};  ///< grid cell [px]
    };

    struct Result {
        /** queryIdx into the current frame's features, trainIdx into the reference's, in
         * increasing queryIdx (as DescriptorMatcher gives them). */
        std::vector<cv::DMatch> matches;
        std::size_t predicted{0};  ///< reference features whose gate meets the image
        std::size_t compared{0};   ///< descriptor pairs compared (brute force: n x m)
    };

    explicit GuidedMatcher(const Params& params) : params_(params) {}

    Result match(const FrameFeatures& current, const FrameFeatures& reference,
                 const CameraIntrinsics& intrinsics, const MotionPrior& prior) const;
    const Params& params() const { return params_; }

  private:
    Params params_;
};

}  // namespace lodestone::vision
