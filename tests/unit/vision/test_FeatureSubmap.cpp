#include "SyntheticFeatures.h"

#include <lodestone/vision/BinaryWordIndex.h>
#include <lodestone/vision/FeatureSubmap.h>
#include <lodestone/vision/SubmapCatalog.h>
#include <lodestone/vision/SubmapMatcher.h>

#include <gtest/gtest.h>

using namespace lodestone;

namespace {
/** A submap of three keyframes along x from `start`, noise-free unless told. */
vision::FeatureSubmap submapOf(const test::FeatureWorld& w, const Eigen::Isometry3d& start,
                               double noise = 0.0) {
    vision::FeatureSubmap s;
    for (int k = 0; k < 3; ++k) {
        const Eigen::Isometry3d X = start * test::planarPose(0.3 * k, 0, 0.1 * k);
        s.add(k, start.inverse() * X, test::forwardCamera(), test::view(w, X, noise, 10 + k));
    }
    return s;
}
}  // namespace

TEST(FeatureSubmap, EachPointLandsWhereEquationOneSays) {
    const auto w = test::FeatureWorld::room(400, 1);
    const Eigen::Isometry3d X0 = test::planarPose(-1, 0.5, 0.3), X1 = test::planarPose(-0.6, 0.7, 0.5);
    vision::FeatureSubmap::Params p;
    p.mergeMaxDistance = -1;  // no merging: every point kept where eq. (1) puts it
    vision::FeatureSubmap s(p);
    const auto f0 = test::view(w, X0, 0, 1), f1 = test::view(w, X1, 0, 2);
    s.add(0, Eigen::Isometry3d::Identity(), test::forwardCamera(), f0);
    s.add(1, X0.inverse() * X1, test::forwardCamera(), f1);
    ASSERT_EQ(s.size(), f0->size() + f1->size());
    const Eigen::Matrix3Xd M = s.points();
    for (std::size_t i = 0; i < f1->size(); ++i) {
        // M = X_0^-1 X_i T_C^R p_i
        const Eigen::Vector3d expected =
            X0.inverse() * X1 * test::forwardCamera() * f1->points.col(static_cast<Eigen::Index>(i)).cast<double>();
        EXPECT_LT((M.col(static_cast<Eigen::Index>(f0->size() + i)) - expected).norm(), 1e-5);
    }
    EXPECT_EQ(s.members().size(), 2u);
    EXPECT_EQ(s.firstNode(), 0);
    EXPECT_EQ(s.lastNode(), 1);
}

TEST(FeatureSubmap, FeaturesSeenAgainAreMergedNotDuplicated) {
    const auto w = test::FeatureWorld::room(400, 2);
    const Eigen::Isometry3d X0 = test::planarPose(0, 0, 0), X1 = test::planarPose(0.2, 0, 0.05);
    vision::FeatureSubmap s;
    const auto f0 = test::view(w, X0, 0.002, 1), f1 = test::view(w, X1, 0.002, 2);
    s.add(0, Eigen::Isometry3d::Identity(), test::forwardCamera(), f0);
    const std::size_t merged = s.add(1, X0.inverse() * X1, test::forwardCamera(), f1);
    // Both views see most of the same wall points.
    EXPECT_GT(merged, f1->size() / 2);
    EXPECT_EQ(s.size(), f0->size() + f1->size() - merged);
    int twice = 0;
    for (int n : s.sightings()) twice += n == 2;
    EXPECT_EQ(static_cast<std::size_t>(twice), merged);
}

TEST(SubmapMatcher, RecoversTheNodeToNodePose) {
    const auto w = test::FeatureWorld::room(1500, 3);
    const Eigen::Isometry3d start = test::planarPose(-1.0, -0.5, 0.2);
    const vision::FeatureSubmap submap = submapOf(w, start, 0.003);
    // Later, the robot comes back near the second keyframe, slightly off.
    const Eigen::Isometry3d X1 = start * test::planarPose(0.3, 0, 0.1);
    const Eigen::Isometry3d query = X1 * test::planarPose(0.15, -0.1, 0.08);
    const auto f = test::view(w, query, 0.003, 99);
    const vision::SubmapMatcher matcher;
    const auto r = matcher.match(submap, *f, test::forwardCamera());
    ASSERT_TRUE(r.success) << r.failure;
    EXPECT_TRUE(r.usedPhase2);
    // Phase 2 starts from the submap keyframe nearest to the query (1 or 2 here).
    ASSERT_TRUE(r.node == 1 || r.node == 2) << r.node;
    const Eigen::Isometry3d Xn = start * test::planarPose(0.3 * r.node, 0, 0.1 * r.node);
    const Eigen::Isometry3d truth = Xn.inverse() * query;
    EXPECT_LT((r.nodeToQuery.translation() - truth.translation()).norm(), 0.01);
    EXPECT_LT(Eigen::AngleAxisd(r.nodeToQuery.linear().transpose() * truth.linear()).angle(), 0.005);
    // Phase 1 put the query where it is in the submap frame.
    EXPECT_LT((r.submapToQuery.translation() - (start.inverse() * query).translation()).norm(), 0.03);
    EXPECT_GT(r.inliers, 50u);
    // A covariance that means something: positive, centimetre-level or below.
    EXPECT_GT(r.covariance(3, 3), 0);
    EXPECT_LT(r.covariance(3, 3), 1e-3);
}

TEST(SubmapMatcher, AWrongCandidateIsRejected) {
    const auto here = test::FeatureWorld::room(1500, 4), elsewhere = test::FeatureWorld::room(1500, 5);
    const vision::FeatureSubmap submap = submapOf(elsewhere, test::planarPose(0, 0, 0));
    const auto f = test::view(here, test::planarPose(0.1, 0, 0.05), 0.003, 7);
    const auto r = vision::SubmapMatcher().match(submap, *f, test::forwardCamera());
    EXPECT_FALSE(r.success);
    EXPECT_FALSE(r.failure.empty());
}

TEST(SubmapMatcher, SameDescriptorsInAnotherGeometryAreRejected) {
    // Perceptual aliasing: the same-looking features, arranged differently.
    auto w = test::FeatureWorld::room(1500, 6);
    const vision::FeatureSubmap submap = submapOf(w, test::planarPose(0, 0, 0));
    std::mt19937 rng(1);
    std::shuffle(w.points.begin(), w.points.end(), rng);
    const auto f = test::view(w, test::planarPose(0.1, 0, 0.05), 0.003, 8);
    const auto r = vision::SubmapMatcher().match(submap, *f, test::forwardCamera());
    EXPECT_FALSE(r.success) << r.inliers << " inliers";
}

TEST(BinaryWordIndex, ThePlaceThatLooksAlikeWinsTheVote) {
    vision::BinaryWordIndex index;
    std::vector<test::FeatureWorld> worlds;
    for (std::uint32_t p = 0; p < 20; ++p) {
        worlds.push_back(test::FeatureWorld::room(400, 100 + p));
        index.add(p, worlds.back().descriptors);
    }
    // A view of place 13 (descriptors with flipped bits) finds place 13 first, by far.
    const auto f = test::view(worlds[13], test::planarPose(0, 0, 0), 0, 5);
    const auto top = index.query(f->descriptors, 3);
    ASSERT_FALSE(top.empty());
    EXPECT_EQ(top[0].first, 13u);
    EXPECT_GT(top[0].second, 30);
    if (top.size() > 1) {
        EXPECT_GT(top[0].second, 5 * top[1].second);
    }
}

TEST(SubmapCatalog, CandidatesByPositionAndAppearanceRespectEligibility) {
    vision::SubmapCatalog catalog;
    std::vector<test::FeatureWorld> worlds;
    for (int k = 0; k < 6; ++k) {
        worlds.push_back(test::FeatureWorld::room(800, 200 + k));
        auto s = std::make_shared<vision::FeatureSubmap>(submapOf(worlds.back(), test::planarPose(0, 0, 0)));
        catalog.add(s, Eigen::Vector3d(10.0 * k, 0, 0));
    }
    const auto f = test::view(worlds[4], test::planarPose(0, 0, 0), 0, 3);
    // Near submap 1 (x = 10), looking like submap 4: both come out.
    auto c = catalog.candidates({10.5, 0, 0}, 2.0, f->descriptors, 2, 2, 10,
                                [](std::size_t) { return true; });
    ASSERT_GE(c.size(), 2u);
    EXPECT_EQ(c[0].submap, 4u);  // appearance first
    EXPECT_GT(c[0].votes, 10);
    const bool hasNear = std::any_of(c.begin(), c.end(), [](const auto& x) { return x.submap == 1; });
    EXPECT_TRUE(hasNear);
    // Submap 4 ineligible (too recent): it is not offered.
    c = catalog.candidates({10.5, 0, 0}, 2.0, f->descriptors, 2, 2, 10,
                           [](std::size_t s) { return s != 4; });
    for (const auto& x : c) EXPECT_NE(x.submap, 4u);
    // A moved centre is found at its new place.
    catalog.setCentre(5, {100, 0, 0});
    c = catalog.candidates({100, 0.5, 0}, 1.0, cv::Mat(), 2, 0, 10, [](std::size_t) { return true; });
    ASSERT_EQ(c.size(), 1u);
    EXPECT_EQ(c[0].submap, 5u);
}
