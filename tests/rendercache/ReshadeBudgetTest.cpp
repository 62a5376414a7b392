// The asynchronous display's reshading budget (rendercache/ReshadeBudget.h):
// no budget reshades every sample; a frame over budget raises the interval
// at once to what fits; a frame well under it lowers the interval one step,
// and only when the lower one would still leave a quarter of the budget.
#include <gtest/gtest.h>

#include "render/RenderCacheSettings.h"
#include "rendercache/ReshadeBudget.h"

using namespace raycache;

TEST(ReshadeBudget, NoBudgetReshadesEverySampleEveryFrame) {
    EXPECT_EQ(reshadeIntervalWithin(0.0, 4, 30.0), 1);
    EXPECT_EQ(reshadeIntervalWithin(-1.0, 1, 30.0), 1);
}

TEST(ReshadeBudget, OverBudgetRaisesTheIntervalToWhatFits) {
    // Every sample costs 1 x 30 ms; 8 ms a frame needs one in four.
    EXPECT_EQ(reshadeIntervalWithin(8.0, 1, 30.0), 4);
    // One in two took 20 ms: every sample 40 ms, one in five fits.
    EXPECT_EQ(reshadeIntervalWithin(8.0, 2, 20.0), 5);
    EXPECT_EQ(reshadeIntervalWithin(0.01, 1, 30.0), kMaxReshadeInterval) << "no more than the largest interval";
}

TEST(ReshadeBudget, UnderBudgetLowersItOneStepWithRoomToSpare) {
    // One in four took 3 ms: every sample 12 ms; one in three would take 4 ms <= 6 ms.
    EXPECT_EQ(reshadeIntervalWithin(8.0, 4, 3.0), 3);
    // One in four took 5 ms: one in three would take 6.7 ms, over 0.75 x 8: keep.
    EXPECT_EQ(reshadeIntervalWithin(8.0, 4, 5.0), 4);
    EXPECT_EQ(reshadeIntervalWithin(8.0, 1, 1.0), 1);
    EXPECT_EQ(reshadeIntervalWithin(8.0, 3, 0.0), 3) << "nothing reshaded, nothing learnt";
}
