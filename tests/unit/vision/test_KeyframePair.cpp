// Two keyframes aligned node to node (alignKeyframePair), then with their depth
// (joinKeyframeDepth), on real Kinect frames against their reconstruction's poses.
#include <gtest/gtest.h>
#include <lodestone/vision/KeyframePair.h>
#include <lodestone/vision/OrbFeatures.h>
#include <lodestone/vision/depth/DepthCloud.h>

#include "ThreeDMatchFrames.h"

using namespace lodestone::vision;

namespace {

/** The proximity closer's matching and RANSAC: as the submap matcher's node-to-node phase. */
struct PairAligner {
    DescriptorMatcher matcher;
    RigidRansac ransac;
    PairAligner()
        : matcher([] {
              DescriptorMatcher::Params p;
              p.ratio = 0.8;
              p.crossCheck = false;
              return p;
          }()),
          ransac([] {
              RigidRansac::Params p;
              p.iterations = 300;
              p.confidence = 0.999;
              p.minInliers = 20;
              p.minInlierRatio = 0.25;
              return p;
          }()) {}
};

double angleOf(const Eigen::Isometry3d& T) { return Eigen::AngleAxisd(T.linear()).angle(); }

}  // namespace

TEST(KeyframePair, RealKinectKeyframesAgreeWithTheReconstructionAndTheDepthConfirmsNoWrongPose) {
    // 3DMatch seq-01, frame 0 against 1 and 2 (a second apart) and against 116 and 422 (after a
    // long way round). Measured: 1 and 2 align to 1.0-1.1 cm and 0.3-0.5 deg of the
    // reconstruction's poses (themselves good to about a centimetre), with the depth joined
    // 0.8-1.1 cm (frame 1's depth and features disagree beyond their covariances); 116 and 422
    // align by 27-34 features to a pose 0.58-0.72 m and 5-8 deg off - a look-alike - which the
    // depth does not join.
    const auto dir = lodestone::test::threeDMatchDir();
    if (!std::filesystem::exists(dir))
        GTEST_SKIP() << "real data absent: " << dir << " (read in place from ../shared/data)";
    const PairAligner aligner;
    const OrbExtractor orb;
    const RgbdFrame reference = lodestone::test::threeDMatchFrame(0);
    const FrameFeatures referenceFeatures = orb.extract(reference);
    const DepthCloud referenceDepth = sampleDepthCloud(reference, {});
    const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();  // the camera is the robot
    for (const int other : {1, 2, 116, 422}) {
        const RgbdFrame query = lodestone::test::threeDMatchFrame(other);
        KeyframePairAlignment a = alignKeyframePair(aligner.matcher, aligner.ransac,
                                                    referenceFeatures, I, orb.extract(query), I, 7);
        const Eigen::Isometry3d truth =
            lodestone::test::threeDMatchPose(0).inverse() * lodestone::test::threeDMatchPose(other);
        const auto errorOf = [&](const Eigen::Isometry3d& T) {
            const Eigen::Isometry3d e = truth.inverse() * T;
            return std::make_pair(e.translation().norm(), angleOf(e));
        };
        if (other < 100) {
            ASSERT_TRUE(a.success) << "frame " << other << ": " << a.matches << " matches";
            const auto [dt, dr] = errorOf(a.referenceToQuery);
            EXPECT_LT(dt, 0.02) << "frame " << other;
            EXPECT_LT(dr, 1.0 * M_PI / 180) << "frame " << other;
        }
        if (!a.success) continue;
        joinKeyframeDepth(PointToPlaneIcp(), referenceDepth, I, sampleDepthCloud(query, {}), I, a);
        const auto [dt, dr] = errorOf(a.referenceToQuery);
        RecordProperty("frame_" + std::to_string(other) + "_joined",
                       a.depthJoined ? std::to_string(100 * dt) + " cm" : "no");
        if (other < 100) EXPECT_TRUE(a.depthJoined) << "frame " << other;
        // Whatever the features said, a pose the depth joined is the right one.
        if (a.depthJoined) {
            EXPECT_LT(dt, 0.02) << "frame " << other;
            EXPECT_LT(dr, 1.0 * M_PI / 180) << "frame " << other;
        }
    }
}
