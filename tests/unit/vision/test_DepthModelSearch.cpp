// DepthModel::nearest searches nanoflann's tree bounded by the gate, or by a previous answer's
// distance where it is given one (as the ICP's passes do): either way, the point it finds must
// be the nearest of them all within the gate (checked here against every point).
#include <gtest/gtest.h>
#include <lodestone/vision/depth/DepthModel.h>

#include <random>

#include "SimTestFrames.h"
#include "SimTestWorlds.h"

using namespace lodestone::vision;

namespace {
/** The least squared distance from p to the model's points (as the model holds them), or
 * infinity. */
float bruteForce(const DepthCloud& model, const Eigen::Vector3f& p) {
    float best = std::numeric_limits<float>::infinity();
    for (Eigen::Index i = 0; i < model.points.cols(); ++i) {
        float d = 0;
        for (int k = 0; k < 3; ++k) d += (p(k) - model.points(k, i)) * (p(k) - model.points(k, i));
        best = std::min(best, d);
    }
    return best;
}

/** Queries around the cloud's points (near the surface, off it, far off it, at and behind the
 * camera), with gates from the ICP's narrowest to beyond its widest, with and without a hint:
 * every answer against the brute force. */
void expectNearestOfAll(const DepthModel& model, const DepthCloud& all, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<Eigen::Index> pick(0, all.points.cols() - 1);
    std::normal_distribution<float> offset(0, 1);
    const float spreads[] = {0.002f, 0.02f, 0.1f, 0.5f};
    const float gates[] = {0.04f, 0.12f, 0.2f, 1.0f};
    int found = 0, checked = 0;
    for (int q = 0; q < 4000; ++q) {
        Eigen::Vector3f p = all.points.col(pick(rng));
        const float spread = spreads[q % 4];
        p += spread * Eigen::Vector3f(offset(rng), offset(rng), offset(rng));
        if (q % 97 == 0) p.z() = -p.z();  // behind the camera
        if (q % 89 == 0) p.z() = 0.01f;   // at it
        const float gate2 = gates[(q / 4) % 4] * gates[(q / 4) % 4];
        const std::int64_t hint = (q % 3 == 0) ? -1 : static_cast<std::int64_t>(pick(rng));
        DepthModel::Nearest nn;
        const bool got = model.nearest(p, gate2, nn, hint);
        const float truth = bruteForce(all, p);
        ++checked;
        ASSERT_EQ(got, truth <= gate2) << "query " << q << " at " << p.transpose();
        if (!got) continue;
        ++found;
        EXPECT_EQ(nn.distance2, truth) << "query " << q;
        EXPECT_EQ(nn.point, all.points.col(nn.index)) << "query " << q;
    }
    EXPECT_GT(found, checked / 3);  // (the queries do reach the cloud)
}
}  // namespace

TEST(DepthModel, TheNearestFoundIsTheNearestOfAllInARoom) {
    const auto sc = lodestone::test::boxScenario("plain");
    const lodestone::sim::World world(sc, 3);
    const auto frame =
        lodestone::test::render(world, lodestone::test::cameraPose({6.6, 1.6, 1.2}, 0.75, 0.4), 11);
    const DepthCloud cloud = sampleDepthCloud(frame, DepthSampling{});
    ASSERT_GT(cloud.size(), 1000u);
    DepthModel model(1);
    model.addReference(cloud, Eigen::Isometry3d::Identity());
    expectNearestOfAll(model, cloud, 1);
}

// Two keyframes (the older one's points seen from the new reference at other directions and
// depths), and points scattered anywhere - behind the camera, beside it, at it.
TEST(DepthModel, TheNearestFoundIsTheNearestOfAllInAnyCloud) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> anywhere(-3, 3);
    DepthCloud scattered;
    scattered.points.resize(3, 3000);
    for (Eigen::Index i = 0; i < scattered.points.cols(); ++i) {
        scattered.points.col(i) << anywhere(rng), anywhere(rng), i % 10 == 0 ? anywhere(rng) / 50 : anywhere(rng);
    }
    scattered.normals = Eigen::Matrix3Xf::Zero(3, 3000);
    scattered.sigma = Eigen::VectorXf::Constant(3000, 0.01f);
    scattered.normalVariance = Eigen::VectorXf::Constant(3000, 1e-4f);
    Eigen::Isometry3d T_new_old = Eigen::Isometry3d::Identity();
    T_new_old.translation() << 0.3, -0.1, -0.5;
    T_new_old.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()).toRotationMatrix();
    DepthModel model(2);
    model.addReference(scattered, Eigen::Isometry3d::Identity());
    model.addReference(scattered, T_new_old);
    DepthCloud all;
    all.points.resize(3, 6000);
    all.points.leftCols(3000) = (T_new_old.cast<float>().linear() * scattered.points).colwise() +
                                T_new_old.cast<float>().translation();
    all.points.rightCols(3000) = scattered.points;
    expectNearestOfAll(model, all, 2);
}
