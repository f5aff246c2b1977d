#include <lodestone/vision/KeyframePair.h>
#include <lodestone/vision/Se3Covariance.h>

namespace lodestone::vision {

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
    // Optical to robot frames: T_rr_qr = C_r T_ro_qo C_q^-1.
    a.referenceToQuery = T_robot_referenceCamera * e.transform * T_robot_queryCamera.inverse();
    // RigidEstimate's covariance: a left perturbation in the reference's optical frame; into its
    // robot frame, then about the motion's own frame.
    const Eigen::Matrix<double, 6, 6> Ad = adjoint(T_robot_referenceCamera);
    a.covariance = leftToRightCovariance(a.referenceToQuery, Ad * e.covariance * Ad.transpose());
    a.inliers = e.inliers.size();
    a.success = true;
    return a;
}

}  // namespace lodestone::vision
