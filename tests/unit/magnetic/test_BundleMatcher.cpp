// Node-bundle matching (paper 000 §2.2): chains of consistent supernode matches.
#include <gtest/gtest.h>
#include <lodestone/magnetic/BundleMatcher.h>

using namespace lodestone::magnetic;

TEST(BundleMatcher, ConsistentMatchesChainIntoABundle) {
    BundleMatcher m({3, 0.3});
    // Query supernodes 100.. match targets 10.. at offset -25 m, with a little scale drift.
    EXPECT_TRUE(m.add(100, {{100, 10, -25.0, 0.5}}, true).empty());
    EXPECT_TRUE(m.add(101, {{101, 11, -25.05, 0.6}, {101, 40, -12.0, 0.4}}, true).empty());
    const auto b = m.add(102, {{102, 12, -25.1, 0.5}}, true);
    ASSERT_EQ(b.size(), 1u);
    EXPECT_EQ(b[0].firstQuery, 100u);
    EXPECT_EQ(b[0].lastQuery, 102u);
    EXPECT_EQ(b[0].firstTarget, 10u);
    EXPECT_EQ(b[0].lastTarget, 12u);
    EXPECT_EQ(b[0].length, 3u);
    EXPECT_NEAR(b[0].meanCost, (0.5 + 0.6 + 0.5) / 3, 1e-12);
    // It goes on while the matches do.
    EXPECT_EQ(m.add(103, {{103, 13, -25.1, 0.5}}, true).size(), 1u);
    // A jump in offset is another place: the chain ends.
    EXPECT_TRUE(m.add(104, {{104, 70, 3.0, 0.5}}, true).empty());
}

TEST(BundleMatcher, AKidnapOrAGapEndsEveryChain) {
    BundleMatcher m({2, 0.3});
    m.add(5, {{5, 1, -10, 0.5}}, true);
    EXPECT_TRUE(m.add(6, {{6, 2, -10, 0.5}}, false).empty());  // the path broke between them
    EXPECT_TRUE(m.add(8, {{8, 4, -10, 0.5}}, true).empty());   // 7 is missing
    EXPECT_EQ(m.add(9, {{9, 5, -10, 0.5}}, true).size(), 1u);
}

TEST(BundleMatcher, TwoPlacesThatBothFitAreBothReported) {
    BundleMatcher m({2, 0.3});
    m.add(50, {{50, 10, -20, 0.9}, {50, 30, -10, 0.4}}, true);
    const auto b = m.add(51, {{51, 11, -20, 0.8}, {51, 31, -10, 0.5}}, true);
    ASSERT_EQ(b.size(), 2u);
    EXPECT_EQ(b[0].lastTarget, 31u);  // cheapest first
    EXPECT_EQ(b[1].lastTarget, 11u);
}
