#include <lodestone/vision/KeyframePair.h>
#include <lodestone/vision/Se3Covariance.h>

namespace lodestone::vision {

namespace {
/** `a`'s optical-frame motion into the robots' frames: T_rr_qr = C_r T_ro_qo C_q^-1; its
 * covariance (a left perturbation in the reference's optical frame) into the reference's robot
 * frame, then about the motion's own frame. */
void intoRobotFrames(const Eigen::Isometry3d& T_robot_referenceCamera,
                     const Eigen::Isometry3d& T_robot_queryCamera, KeyframePairAlignment& a) {
    a.referenceToQuery =
        T_robot_referenceCamera * a.opticalReferenceToQuery * T_robot_queryCamera.inverse();
    const Eigen::Matrix<double, 6, 6> Ad = adjoint(T_robot_referenceCamera);
    a.covariance = leftToRightCovariance(a.referenceToQuery, Ad * a.opticalCovariance * Ad.transpose());
}
}  // namespace

KeyframePairAlignment alignKeyframePair(const DescriptorMatcher& matcher, const RigidRansac& ransac,
                                        const FrameFeatures& reference,
                                        const Eigen::Isometry3d& T_robot_referenceCamera,
                                        const FrameFeatures& query,
                                        const Eigen::Isometry3d& T_robot_queryCamera,
                                        std::uint64_t seed) {
    KeyframePairAlignment a;
    if (reference.size() == 0 || query.size() == 0) return a;
    const auto matches = matcher.match(query.descriptors, reference.descriptors);
    a.matches = matches.size();
    if (matches.size() < static_cast<std::size_t>(ransac.params().minInliers)) return a;
    const auto n = static_cast<Eigen::Index>(matches.size());
    Eigen::Matrix3Xd src(3, n), dst(3, n);
    for (Eigen::Index k = 0; k < n; ++k) {
        const auto& m = matches[static_cast<std::size_t>(k)];
        src.col(k) = query.points.col(m.queryIdx).cast<double>();
        dst.col(k) = reference.points.col(m.trainIdx).cast<double>();
    }
    const RigidEstimate e = ransac.estimate(src, dst, seed);
    if (!e.success) return a;
    a.opticalReferenceToQuery = e.transform;
    a.opticalCovariance = e.covariance;
    intoRobotFrames(T_robot_referenceCamera, T_robot_queryCamera, a);
    a.inliers = e.inliers.size();
    a.success = true;
    return a;
}

void joinKeyframeDepth(const PointToPlaneIcp& icp, const DepthCloud& reference,
                       const Eigen::Isometry3d& T_robot_referenceCamera, const DepthCloud& query,
                       const Eigen::Isometry3d& T_robot_queryCamera, KeyframePairAlignment& a) {
    if (!a.success || reference.size() == 0 || query.size() == 0) return;
    DepthModel model(1);
    model.addReference(reference, Eigen::Isometry3d::Identity());
    const MotionPrior measured{a.opticalReferenceToQuery, a.opticalCovariance};
    const DepthAlignment d = icp.align(model, query, a.opticalReferenceToQuery, &measured);
    if (!d.success) return;
    a.opticalReferenceToQuery = d.T_ref_cur;
    a.opticalCovariance = d.covariance;
    a.depthJoined = true;
    a.depthDisagreed = d.disagreed;
    a.depthCorrespondences = d.correspondences;
    intoRobotFrames(T_robot_referenceCamera, T_robot_queryCamera, a);
}

}  // namespace lodestone::vision
