#include <lodestone/vision/KeyframePair.h>
#include <lodestone/vision/Se3Covariance.h>
#include <lodestone/vision/SubmapMatcher.h>

#include <chrono>
#include <cmath>

namespace lodestone::vision {

namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

double angleOf(const Eigen::Isometry3d& T) { return Eigen::AngleAxisd(T.linear()).angle(); }

/** Matched pairs as two point matrices. */
void gather(const std::vector<cv::DMatch>& matches, const Eigen::Matrix3Xd& query,
            const Eigen::Matrix3Xd& train, Eigen::Matrix3Xd& src, Eigen::Matrix3Xd& dst) {
    src.resize(3, static_cast<Eigen::Index>(matches.size()));
    dst.resize(3, static_cast<Eigen::Index>(matches.size()));
    for (std::size_t k = 0; k < matches.size(); ++k) {
        src.col(static_cast<Eigen::Index>(k)) = query.col(matches[k].queryIdx);
        dst.col(static_cast<Eigen::Index>(k)) = train.col(matches[k].trainIdx);
    }
}
}  // namespace

SubmapMatcher::Params::Params() {
    matcher.ratio = 0.8;  // many similar features in a submap: keep only distinctive matches
    matcher.crossCheck = false;  // the ratio test and RANSAC suffice; a second pass doubles the cost
    phase1.iterations = 400;
    phase1.threshold = 0.08;  // points accumulated through odometry: looser than VO
    phase1.depthScale = 0;    // robot / submap frames: z is height, not depth
    phase1.minInliers = 20;
    phase1.minInlierRatio = 0.2;
    phase1.pointNoise = 0.03;
    phase1.depthNoise = 0;
    phase1.confidence = 0.999;
    phase2.iterations = 300;
    phase2.confidence = 0.999;
    phase2.minInliers = 15;
    phase2.minInlierRatio = 0.25;
}

SubmapMatcher::SubmapMatcher() : SubmapMatcher(Params{}) {}

SubmapMatcher::SubmapMatcher(Params params)
    : params_(std::move(params)),
      matcher_(params_.matcher),
      phase1_(params_.phase1),
      phase2_(params_.phase2) {}

SubmapMatcher::Result SubmapMatcher::match(const FeatureSubmap& submap, const FrameFeatures& query,
                                           const Eigen::Isometry3d& T_robot_queryCamera,
                                           std::uint64_t seed) const {
    Result r;
    const auto t0 = Clock::now();
    if (submap.empty() || submap.size() < static_cast<std::size_t>(params_.phase1.minInliers) ||
        query.size() < static_cast<std::size_t>(params_.phase1.minInliers)) {
        r.failure = "too few features";
        return r;
    }
    // Phase 1: keyframe (robot frame) -> submap frame.
    const Eigen::Matrix3Xd queryRobot = T_robot_queryCamera * query.points.cast<double>();
    // The features seen most often first, at most phase1MaxFeatures of them: the stable ones,
    // and a bounded matching cost however large the submap grew.
    const std::vector<int>& order = submap.strongestFirst();
    const std::size_t used = std::min(order.size(), params_.phase1MaxFeatures);
    cv::Mat trainDescriptors(static_cast<int>(used), 32, CV_8U);
    Eigen::Matrix3Xd trainPoints(3, static_cast<Eigen::Index>(used));
    {
        const Eigen::Matrix3Xd all = submap.points();
        for (std::size_t k = 0; k < used; ++k) {
            submap.descriptors().row(order[k]).copyTo(trainDescriptors.row(static_cast<int>(k)));
            trainPoints.col(static_cast<Eigen::Index>(k)) = all.col(order[k]);
        }
    }
    const auto matches = matcher_.match(query.descriptors, trainDescriptors);
    r.matches = matches.size();
    if (matches.size() < static_cast<std::size_t>(params_.phase1.minInliers)) {
        r.failure = "too few matches";
        r.phase1Ms = msSince(t0);
        return r;
    }
    Eigen::Matrix3Xd src, dst;
    gather(matches, queryRobot, trainPoints, src, dst);
    const RigidEstimate p1 = phase1_.estimate(src, dst, seed);
    r.phase1Ms = msSince(t0);
    if (!p1.success) {
        r.failure = "phase 1 RANSAC";
        return r;
    }
    r.inliers = p1.inliers.size();
    r.submapToQuery = p1.transform;

    // Phase 2: the nearest keyframe of the submap, node to node.
    const auto t1 = Clock::now();
    const FeatureSubmap::Member& m = submap.nearestMember(p1.transform);
    r.node = m.node;
    const Eigen::Isometry3d fromPhase1 = m.T_submap_robot.inverse() * p1.transform;
    if (m.features && m.features->size() > 0) {
        const KeyframePairAlignment p2 = alignKeyframePair(
            matcher_, phase2_, *m.features, m.T_robot_camera, query, T_robot_queryCamera, seed);
        r.phase2Matches = p2.matches;
        if (p2.success) {
            const Eigen::Isometry3d diff = fromPhase1.inverse() * p2.referenceToQuery;
            if (diff.translation().norm() <= params_.agreementDistance &&
                angleOf(diff) <= params_.agreementAngle) {
                r.phase2Inliers = p2.inliers;
                r.usedPhase2 = true;
                r.nodeToQuery = p2.referenceToQuery;
                r.covariance = p2.covariance;
            }
        }
    }
    r.phase2Ms = msSince(t1);
    if (!r.usedPhase2) {
        // Without the node-level check, phase 1 alone must be stronger.
        if (!params_.phase1Fallback || r.inliers < params_.fallbackMinInliers) {
            r.failure = "phase 2";
            return r;
        }
        r.nodeToQuery = fromPhase1;
        const Eigen::Matrix<double, 6, 6> Ad = adjoint(m.T_submap_robot.inverse());
        r.covariance = params_.fallbackInflation *
                       leftToRightCovariance(fromPhase1, Ad * p1.covariance * Ad.transpose());
    }
    r.success = true;
    return r;
}

}  // namespace lodestone::vision
