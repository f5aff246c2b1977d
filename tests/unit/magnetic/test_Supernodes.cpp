// Supernodes (paper 000 §2.2): distance resampling, overlap, eq. (2) cost and the KD-tree.
#include <gtest/gtest.h>
#include <lodestone/magnetic/DistanceResampler.h>
#include <lodestone/magnetic/FieldFeatures.h>
#include <lodestone/magnetic/SupernodeIndex.h>
#include <lodestone/magnetic/SupernodeTrack.h>

#include "SyntheticField.h"

using namespace lodestone::magnetic;

TEST(DistanceResampler, OutputIsSpacedByDistanceWhateverTheSpeed) {
    const lodestone::test::SyntheticField field(1);
    DistanceResampler r(0.05);
    std::vector<DistanceResampler::Sample> out;
    // Readings every 10 ms while the speed swings between 0.05 and 1.45 m/s: a time-spaced
    // sequence would stretch and squeeze the field.
    double s = 0;
    for (int k = 0; s < 10.0; ++k) {
        const double t = 0.01 * k;
        s += 0.01 * (0.75 + 0.7 * std::sin(t));
        for (auto& o : r.add(s, field.at(s))) out.push_back(o);
    }
    ASSERT_GT(out.size(), 190u);
    for (std::size_t i = 0; i < out.size(); ++i) {
        EXPECT_NEAR(out[i].s, out.front().s + 0.05 * static_cast<double>(i), 1e-9) << i;
        // Bin means of a smooth field: close to the field at the bin centre.
        EXPECT_NEAR(out[i].value[0], field.at(out[i].s)[0], 0.35) << i;
    }
}

TEST(DistanceResampler, EmptyBinsAreInterpolatedAndResetBreaksThePath) {
    DistanceResampler r(0.1);
    Eigen::VectorXd v(1);
    v << 0;
    r.add(0.01, v);
    v << 1;
    auto out = r.add(0.12, v);  // closes bin 0
    ASSERT_EQ(out.size(), 1u);
    v << 4;
    out = r.add(0.45, v);  // closes bin 1; bins 2 and 3 are empty
    ASSERT_EQ(out.size(), 1u);
    v << 5;
    out = r.add(0.51, v);  // closes bin 4, fills 2 and 3 between bin 1 (1) and bin 4 (4)
    ASSERT_EQ(out.size(), 3u);
    EXPECT_NEAR(out[0].s, 0.25, 1e-12);
    EXPECT_NEAR(out[0].value[0], 2.0, 1e-12);
    EXPECT_NEAR(out[1].value[0], 3.0, 1e-12);
    EXPECT_NEAR(out[2].value[0], 4.0, 1e-12);
    r.reset();
    out = r.add(3.0, v);
    EXPECT_TRUE(out.empty());  // nothing interpolated across the break
    out = r.add(3.15, v);
    EXPECT_EQ(out.size(), 1u);
}

TEST(SupernodeTrack, SupernodesOverlapEveryStrideAndNeverSpanAKidnap) {
    const lodestone::test::SyntheticField field(2);
    SupernodeTrack track({0.05, 2.0, 0.25}, 2);
    std::vector<Supernode> made;
    for (double s = 0; s < 10.0; s += 0.01) {
        const int segment = s < 6.0 ? 0 : 1;
        for (auto& sn : track.add(s, field.at(s), static_cast<std::size_t>(s * 10), segment))
            made.push_back(sn);
    }
    ASSERT_GE(made.size(), 2u);
    EXPECT_EQ(track.samplesPerSupernode(), 40u);
    for (std::size_t i = 0; i < made.size(); ++i) {
        const auto& sn = made[i];
        EXPECT_EQ(sn.last - sn.first, 40u);
        EXPECT_EQ(sn.vector.size(), 80);
        EXPECT_NEAR(sn.vector.sum(), 0.0, 1e-3);  // mean removed
        const auto& samples = track.samples();
        EXPECT_EQ(samples[sn.first].segment, samples[sn.last - 1].segment) << "spans the kidnap";
        if (i > 0 && made[i - 1].segment == sn.segment) {
            EXPECT_EQ(sn.first - made[i - 1].first, 5u);
        }
    }
    // Segment 0 holds 119 samples (the bin open at the kidnap is dropped with the path):
    // (119 - 40) / 5 + 1 = 16 supernodes; segment 1 starts afresh 2 m after the kidnap.
    std::size_t first = 0;
    for (const auto& sn : made) first += sn.segment == 0;
    EXPECT_EQ(first, 16u);
    EXPECT_GT(track.samples()[made[first].first].s, 6.0);
}

TEST(SupernodeTrack, CostIsTheRmsOfTheFieldDifference) {
    SupernodeTrack a({0.1, 1.0, 1.0}, 2), b({0.1, 1.0, 1.0}, 2);
    Eigen::VectorXd va(2), vb(2);
    std::vector<Supernode> sa, sb;
    for (int k = 0; k < 12; ++k) {
        const double s = 0.1 * k + 0.05;
        va << 50 + std::sin(s), -40;
        vb << 50 + std::sin(s) + 0.3, -40 - 0.4;  // the same shape, levels off by (0.3, -0.4)
        for (auto& n : a.add(s, va, 0, 0)) sa.push_back(n);
        for (auto& n : b.add(s, vb, 0, 0)) sb.push_back(n);
    }
    ASSERT_FALSE(sa.empty());
    ASSERT_FALSE(sb.empty());
    EXPECT_NEAR(SupernodeTrack::cost(sa[0], sb[0]), std::sqrt((0.09 + 0.16) / 2), 1e-5);
    EXPECT_NEAR(SupernodeTrack::cost(sa[0], sa[0]), 0.0, 1e-6);
}

TEST(SupernodeTrack, ARevisitHalfAStrideOutOfPhaseStillMatchesOnceSlid) {
    // One track: a stretch of field, a different stretch, then the first again, started
    // 0.125 m (half the 0.25 m stride) later in phase, so no stored supernode lines up with
    // the revisit's within less than half a stride.
    const lodestone::test::SyntheticField field(5, 30.0, 6.0), other(6, 30.0, 6.0);
    SupernodeTrack t({0.05, 2.0, 0.25}, 2);
    std::vector<Supernode> first, revisit;
    double s = 0;
    const auto drive = [&](const lodestone::test::SyntheticField& f, double from, double length,
                           std::vector<Supernode>* keep) {
        for (double x = from; x < from + length; x += 0.005, s += 0.005) {
            for (auto& n : t.add(s, f.at(x), 0, 0))
                if (keep) keep->push_back(n);
        }
    };
    drive(field, 0.0, 10.0, &first);
    drive(other, 0.0, 5.0, nullptr);
    drive(field, 0.125, 8.0, &revisit);
    ASSERT_GT(revisit.size(), 10u);
    double plain = 0, slid = 0;
    std::size_t count = 0;
    for (const auto& q : revisit) {
        // The stored supernode nearest the same place, by the true phase.
        float best = INFINITY, bestSlid = INFINITY;
        for (const auto& c : first) {
            best = std::min(best, SupernodeTrack::cost(q, c));
            bestSlid = std::min(bestSlid, t.alignedCost(q, c, t.halfStrideSamples()).first);
        }
        plain += best;
        slid += bestSlid;
        ++count;
    }
    plain /= double(count);
    slid /= double(count);
    // Half a stride out of phase costs about max_cost (1.5 uT) on this steep field; slid by
    // whole samples (0.05 m), what is left is the resampling's own phase error (<= 0.025 m).
    EXPECT_GT(plain, 1.0);
    EXPECT_LT(slid, 0.5 * plain);
    EXPECT_LT(slid, 1.0) << plain;
    // Off the track, or across a segment boundary: no cost.
    EXPECT_TRUE(std::isinf(t.costAt(revisit.back(), t.samples().size())));
}

TEST(SupernodeIndex, FindsTheRevisitedStretchAmongManyAndAnUnseenFieldIsFar) {
    const lodestone::test::SyntheticField field(3, 200.0), other(99, 20.0);
    SupernodeTrack track({0.05, 2.0, 0.25}, 2);
    SupernodeIndex index(2, track.samplesPerSupernode());
    std::vector<Supernode> stored;
    for (double s = 0; s < 200.0; s += 0.02) {
        for (auto& sn : track.add(s, field.at(s), 0, 0)) {
            index.add(sn);
            stored.push_back(sn);
        }
    }
    ASSERT_GT(index.size(), 700u);
    // Revisit of 120.3 .. 122.3 m with 0.3 uT of reading noise.
    SupernodeTrack again({0.05, 2.0, 0.25}, 2), elsewhere({0.05, 2.0, 0.25}, 2);
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0, 0.3);
    std::optional<Supernode> q, far;
    for (double s = 0; s < 2.05 && !q; s += 0.02) {
        Eigen::VectorXd v = field.at(120.3 + s);
        v[0] += noise(rng);
        v[1] += noise(rng);
        for (auto& sn : again.add(s, v, 0, 0)) q = sn;
    }
    for (double s = 0; s < 2.05 && !far; s += 0.02) {
        for (auto& sn : elsewhere.add(s, other.at(s), 0, 0)) far = sn;
    }
    ASSERT_TRUE(q && far);
    const auto near = index.nearest(*q, 5);
    ASSERT_FALSE(near.empty());
    const double at = track.samples()[stored[near.front()].first].s;
    EXPECT_NEAR(at, 120.3, 0.15);  // within the stride's reach
    EXPECT_LT(SupernodeTrack::cost(*q, stored[near.front()]), 1.0);
    // A field the track never saw: its nearest stored supernode costs far more.
    const auto best = index.nearest(*far, 1);
    ASSERT_EQ(best.size(), 1u);
    EXPECT_GT(SupernodeTrack::cost(*far, stored[best.front()]), 1.5);
}

TEST(FieldFeatures, InvariantFeaturesIgnoreHeadingVectorOnesTurnWithIt) {
    const Eigen::Vector3d b(10, 5, -40);
    const auto i0 = fieldFeature(b, 0.0, FieldMode::Invariant),
               i1 = fieldFeature(b, 1.0, FieldMode::Invariant);
    EXPECT_NEAR((i0 - i1).norm(), 0.0, 1e-12);
    EXPECT_NEAR(i0[0], b.norm(), 1e-12);
    const auto v = fieldFeature(b, M_PI / 2, FieldMode::Vector);
    EXPECT_NEAR(v[0], -5, 1e-12);
    EXPECT_NEAR(v[1], 10, 1e-12);
    EXPECT_FALSE(usableReading(Eigen::Vector3d(std::nan(""), 0, 0), 1000));
    EXPECT_FALSE(usableReading(Eigen::Vector3d(0, INFINITY, 0), 1000));
    EXPECT_FALSE(usableReading(Eigen::Vector3d(0, 0, 1200), 1000));
    EXPECT_TRUE(usableReading(b, 1000));
    EXPECT_THROW(parseFieldMode("vectr"), std::invalid_argument);
}
