// The where-caching-pays model (bench/CachingPayModel.h) on frames whose
// parts are known: its two ends (no cache, the ideal cache) and a case
// worked by hand.
#include <gtest/gtest.h>

#include "bench/CachingPayModel.h"

#include <limits>

using namespace raycache;

namespace {

CachingPayParts partsOfAFrame() {
    CachingPayParts p;
    p.uncachedMs = 100.0;
    p.idealMs = 60.0;       // 44 ms of trees, 4 ms of lookups
    p.idealLookupMs = 4.0;
    p.leavingRays = 1000;
    return p;
}

}  // namespace

TEST(CachingPayModel, TheIdealCacheIsPredictedAsMeasured) {
    CachingPayParts p = partsOfAFrame();
    p.hitRate = 1.0;
    p.lookupMs = p.idealLookupMs;
    EXPECT_DOUBLE_EQ(cacheableTreeMs(p), 44.0);
    EXPECT_DOUBLE_EQ(cacheableShare(p), 0.44);
    EXPECT_DOUBLE_EQ(predictedFrameMs(p), p.idealMs);
    EXPECT_DOUBLE_EQ(predictedSpeedup(p), 100.0 / 60.0);
    // Free lookups would leave only the frame outside the trees: 100 - 44.
    EXPECT_DOUBLE_EQ(freeCacheSpeedup(p), 100.0 / 56.0);
    EXPECT_GT(freeCacheSpeedup(p), predictedSpeedup(p));
}

TEST(CachingPayModel, AFrameOfTreesAloneHasNoBound) {
    CachingPayParts p = partsOfAFrame();
    p.idealMs = p.idealLookupMs;  // nothing but trees and their lookups
    EXPECT_DOUBLE_EQ(cacheableShare(p), 1.0);
    EXPECT_EQ(freeCacheSpeedup(p), std::numeric_limits<double>::infinity());
}

TEST(CachingPayModel, ACacheThatNeverHitsCostsItsLookupsAndFrameEnd) {
    CachingPayParts p = partsOfAFrame();
    p.hitRate = 0.0;
    p.lookupMs = 5.0;
    p.frameEndMs = 2.5;
    EXPECT_DOUBLE_EQ(predictedFrameMs(p), 107.5);
    EXPECT_LT(predictedSpeedup(p), 1.0);
}

TEST(CachingPayModel, HalfTheTreesAnsweredByHand) {
    CachingPayParts p = partsOfAFrame();
    p.hitRate = 0.5;
    p.lookupMs = 8.0;   // a slower lookup than the ideal frame's
    p.frameEndMs = 1.0;
    // 100 - 0.5 * 44 + 8 + 1 = 87
    EXPECT_DOUBLE_EQ(predictedFrameMs(p), 87.0);
    EXPECT_DOUBLE_EQ(predictedSpeedup(p), 100.0 / 87.0);
}

TEST(CachingPayModel, AnEmptyFrameHasNoShareAndNoSpeedup) {
    const CachingPayParts p;
    EXPECT_EQ(cacheableShare(p), 0.0);
    EXPECT_EQ(predictedSpeedup(p), 0.0);
    EXPECT_EQ(freeCacheSpeedup(p), 0.0);
}
