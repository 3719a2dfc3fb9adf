// The order in which a spread study hands out its runs and the time that takes
// (tools/studies/RunSchedule): largest first, each to the rank free first.
#include "studies/RunSchedule.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

using namespace lsdem;

TEST(RunSchedule, LargestFirstKeepsTiesInOrder)
{
    EXPECT_EQ(largestFirst({2, 5, 1, 5, 3}), (std::vector<size_t>{1, 3, 4, 0, 2}));
    EXPECT_TRUE(largestFirst({}).empty());
}

// One rank does everything in turn (the sum); with a rank per run the longest run decides;
// in between, the longest-processing-time rule by hand: {3, 3, 2, 2, 2} on 2 ranks gives
// 3+2+2 and 3+2, so 7 (the best split, 3+3 and 2+2+2, is 6: the rule is within 4/3 of the
// best, Graham 1969, and that is what the estimate promises, not more).
TEST(RunSchedule, MakespanOfLargestFirst)
{
    const std::vector<double> runs = {2, 7, 1, 4, 4, 3};
    EXPECT_DOUBLE_EQ(largestFirstMakespan(runs, 1), std::accumulate(runs.begin(), runs.end(), 0.0));
    EXPECT_DOUBLE_EQ(largestFirstMakespan(runs, 0), 21.0);  // no ranks counts as one
    EXPECT_DOUBLE_EQ(largestFirstMakespan(runs, 6), 7.0);
    EXPECT_DOUBLE_EQ(largestFirstMakespan(runs, 100), 7.0);
    // 2 ranks: 7 | 4 4 → 7+2 = 9, 4+4 = 8, then 3 to the rank at 8 → 11, 1 to the rank at 9
    // → 10: 11.
    EXPECT_DOUBLE_EQ(largestFirstMakespan(runs, 2), 11.0);
    EXPECT_DOUBLE_EQ(largestFirstMakespan({3, 3, 2, 2, 2}, 2), 7.0);
    EXPECT_DOUBLE_EQ(largestFirstMakespan({}, 4), 0.0);
}

TEST(RunSchedule, SharesSayWhoDidHowMany)
{
    RunShares shares(3);
    for (int rank : {0, 2, 2, 1, 2}) shares.add(rank);
    EXPECT_EQ(shares.text(), "5 runs over 3 ranks (runs per rank: 1 1 3)");
}
