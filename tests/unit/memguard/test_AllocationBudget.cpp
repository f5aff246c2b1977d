// memguard::AllocationBudget with the hooks this test binary links: operator new and MRPT's
// aligned allocator charged, the allocation past the limit refused before it is made.
#include <gtest/gtest.h>
#include <lodestone/memguard/AllocationBudget.h>
#include <mrpt/math/CMatrixDynamic.h>

#include <deque>
#include <new>
#include <string>
#include <vector>

#include "TestPaths.h"

using lodestone::memguard::AllocationBudget;

TEST(AllocationBudget, TheHooksAreLinkedIntoTestBinaries) {
    EXPECT_TRUE(AllocationBudget::hooksInstalled());
}

TEST(AllocationBudget, RefusesTheAllocationPastItsLimitThenStandsAside) {
    AllocationBudget budget(1 << 20);
    std::vector<char> small(512 << 10);
    EXPECT_GE(budget.charged(), 512u << 10);
    EXPECT_FALSE(budget.exceeded());
    EXPECT_THROW(std::vector<char>(1 << 20), std::bad_alloc);
    EXPECT_TRUE(budget.exceeded());
    EXPECT_EQ(budget.refused(), 1u << 20);
    // Refused once, it stands aside: the error can still be built and reported.
    std::string message(4 << 20, 'x');
    EXPECT_EQ(message.size(), 4u << 20);
}

TEST(AllocationBudget, ASizeFieldOfGigabytesCostsNothing) {
    const std::size_t before = lodestone::test::residentSetBytes();
    {
        AllocationBudget budget(64 << 20);
        std::string label;
        EXPECT_THROW(label.resize(0xF0000000u), std::bad_alloc);  // MRPT reads strings so
        EXPECT_EQ(budget.refused(), 0xF0000001u);                 // (the terminating zero)
    }
    EXPECT_LT(lodestone::test::residentSetBytes(), before + (50u << 20));
}

TEST(AllocationBudget, MrptsAlignedAllocatorIsChargedToo) {
    // CMatrixDynamic stores through mrpt::aligned_malloc, which returns null on a huge size
    // (and aligned_calloc then memsets it: a crash); with a budget it throws instead.
    AllocationBudget budget(16 << 20);
    mrpt::math::CMatrixDynamic<std::uint16_t> m;
    m.resize(100, 100);
    EXPECT_GE(budget.charged(), 100u * 100u * 2u);
    EXPECT_THROW(m.resize(100000, 100000), std::bad_alloc);
    EXPECT_TRUE(budget.exceeded());
}

TEST(AllocationBudget, NothrowNewReturnsNullAndBudgetsNest) {
    AllocationBudget outer(64 << 20);
    {
        AllocationBudget inner(1 << 10);
        EXPECT_EQ(new (std::nothrow) char[1 << 20], nullptr);
        EXPECT_TRUE(inner.exceeded());
    }
    EXPECT_FALSE(outer.exceeded());
    std::vector<char> v(1 << 20);  // the outer budget applies again
    EXPECT_GE(outer.charged(), 1u << 20);
}

TEST(AllocationBudget, WithoutABudgetNothingIsRefused) {
    std::vector<char> v(64 << 20);
    EXPECT_EQ(v.size(), 64u << 20);
}

TEST(AllocationBudget, SmallBlocksPastTheLimitAreRefusedOnlyPastTheSlack) {
    // What code that may not throw allocates near the limit (MRPT building an exception's call
    // stack) is small: refusing it would end in std::terminate. The next large block past the
    // limit is refused; small ones only once the slack is used up too (a std::deque resized
    // to a damaged count grows in 512-byte blocks).
    {
        AllocationBudget budget(1 << 20);
        std::vector<std::string> many;
        for (int i = 0; i < 64; ++i) many.emplace_back(32 << 10, 'x');  // 2 MB in 32 kB blocks
        EXPECT_FALSE(budget.exceeded());
        EXPECT_GT(budget.charged(), 2u << 20);
        EXPECT_THROW(std::vector<char>(AllocationBudget::kSmallestRefused), std::bad_alloc);
        EXPECT_EQ(budget.refused(), AllocationBudget::kSmallestRefused);
    }
    {
        AllocationBudget budget(1 << 20);
        std::deque<std::uint64_t> endless;
        EXPECT_THROW(endless.resize(std::size_t{1} << 32), std::bad_alloc);
        EXPECT_TRUE(budget.exceeded());
        EXPECT_LE(budget.charged(), (1u << 20) + AllocationBudget::kSmallBlockSlack);
    }
}
