#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "bench/SpeedupInterval.h"

namespace raycache {
namespace {

TEST(SpeedupInterval, ConstantTimesGiveTheExactRatioWithAZeroWidthInterval) {
    const std::vector<double> baseline(8, 10.0), variant(8, 4.0);
    const SpeedupInterval s = bootstrapSpeedup(baseline, variant);
    EXPECT_DOUBLE_EQ(s.speedup, 2.5);
    EXPECT_DOUBLE_EQ(s.low, 2.5);
    EXPECT_DOUBLE_EQ(s.high, 2.5);
    EXPECT_EQ(s.pairs, 8);
    EXPECT_FALSE(s.containsOne());
    EXPECT_DOUBLE_EQ(s.relativeHalfWidth(), 0.0);
}

TEST(SpeedupInterval, ResamplingKeepsRoundsPaired) {
    // Machine noise moves both variants of a round together: every round the
    // variant takes exactly half the baseline's time. Paired resampling sees
    // a ratio of exactly 2 in every resample; unpaired resampling would mix
    // slow and fast rounds and give a wide interval.
    const std::vector<double> baseline = {10, 30, 12, 50, 11, 45, 20, 13, 38, 16};
    std::vector<double> variant;
    for (double b : baseline) variant.push_back(b / 2.0);
    const SpeedupInterval s = bootstrapSpeedup(baseline, variant);
    EXPECT_DOUBLE_EQ(s.speedup, 2.0);
    EXPECT_DOUBLE_EQ(s.low, 2.0);
    EXPECT_DOUBLE_EQ(s.high, 2.0);
}

TEST(SpeedupInterval, MedianOfKnownDataAndTheIntervalAroundIt) {
    // Medians 11 and 5.5 (even counts: mean of the middle two): speed-up 2.
    const std::vector<double> baseline = {9, 10, 12, 14, 8, 11, 11, 13};
    const std::vector<double> variant = {6, 5, 5, 6, 4, 7, 5, 6};
    const SpeedupInterval s = bootstrapSpeedup(baseline, variant);
    EXPECT_DOUBLE_EQ(s.speedup, 11.0 / 5.5);
    EXPECT_LT(s.low, s.speedup);
    EXPECT_GT(s.high, s.speedup);
    // Bounds of any resample: smallest baseline / largest variant and back.
    EXPECT_GE(s.low, 8.0 / 7.0);
    EXPECT_LE(s.high, 14.0 / 4.0);
    EXPECT_FALSE(s.containsOne());
}

TEST(SpeedupInterval, MeanStatisticForCameraPaths) {
    BootstrapSettings settings;
    settings.statistic = TimeStatistic::Mean;
    const SpeedupInterval s =
        bootstrapSpeedup(std::vector<double>{10, 20, 60}, std::vector<double>{10, 10, 10}, settings);
    EXPECT_DOUBLE_EQ(s.speedup, 3.0);  // 30 / 10; the median would say 2
}

TEST(SpeedupInterval, SameSeedSameInterval) {
    std::mt19937_64 rng(7);
    std::normal_distribution<double> noise(0.0, 2.0);
    std::vector<double> b, v;
    for (int i = 0; i < 15; ++i) {
        b.push_back(20.0 + noise(rng));
        v.push_back(15.0 + noise(rng));
    }
    const SpeedupInterval first = bootstrapSpeedup(b, v), second = bootstrapSpeedup(b, v);
    EXPECT_EQ(first.low, second.low);
    EXPECT_EQ(first.high, second.high);
    BootstrapSettings other;
    other.seed = 99;
    const SpeedupInterval reseeded = bootstrapSpeedup(b, v, other);
    EXPECT_TRUE(reseeded.low != first.low || reseeded.high != first.high);
}

TEST(SpeedupInterval, CoversTheTrueRatioAboutNineteenTimesInTwenty) {
    // 400 simulated benchmarks of 30 paired rounds: baseline ~ N(30, 3),
    // variant ~ N(20, 2), independent, true ratio of medians 1.5.
    std::mt19937_64 rng(2026);
    std::normal_distribution<double> base(30.0, 3.0), var(20.0, 2.0);
    BootstrapSettings settings;
    settings.resamples = 1000;
    int covered = 0;
    const int trials = 400;
    for (int t = 0; t < trials; ++t) {
        std::vector<double> b, v;
        for (int i = 0; i < 30; ++i) {
            b.push_back(base(rng));
            v.push_back(var(rng));
        }
        const SpeedupInterval s = bootstrapSpeedup(b, v, settings);
        if (s.low <= 1.5 && 1.5 <= s.high) ++covered;
    }
    // Percentile intervals of a median ratio run a little below nominal at n = 30.
    EXPECT_GE(covered, trials * 85 / 100);
    EXPECT_LE(covered, trials * 99 / 100);
}

TEST(SpeedupInterval, ContainsOneIsInclusiveAndNeedsAnInterval) {
    EXPECT_TRUE((SpeedupInterval{1.1, 0.99, 1.2, 10}.containsOne()));
    EXPECT_TRUE((SpeedupInterval{1.1, 1.0, 1.2, 10}.containsOne()));
    EXPECT_TRUE((SpeedupInterval{0.9, 0.8, 1.0, 10}.containsOne()));
    EXPECT_FALSE((SpeedupInterval{1.1, 1.01, 1.2, 10}.containsOne()));
    EXPECT_FALSE((SpeedupInterval{0.9, 0.8, 0.99, 10}.containsOne()));
    EXPECT_FALSE((SpeedupInterval{1.0, 0.5, 1.5, 1}.containsOne()));  // one pair: no interval at all
}

TEST(SpeedupInterval, IdenticalDistributionsReadAsNoMeasurableDifference) {
    // The case: a variant that does the same work as the baseline, timed on a noisy machine.
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> ms(24.5, 48.6);
    std::vector<double> b, v;
    for (int i = 0; i < 12; ++i) {
        b.push_back(ms(rng));
        v.push_back(ms(rng));
    }
    const SpeedupInterval s = bootstrapSpeedup(b, v);
    ASSERT_TRUE(s.known());
    EXPECT_TRUE(s.containsOne()) << s.low << "–" << s.high;
    EXPECT_EQ(describeSpeedup(s).rfind("no measurable difference (", 0), 0u) << describeSpeedup(s);
}

TEST(SpeedupInterval, DescriptionsOfEachCase) {
    EXPECT_EQ(describeSpeedup({1.18, 1.104, 1.266, 10}), "1.18× (95 % CI 1.10–1.27)");
    EXPECT_EQ(describeSpeedup({1.61, 0.8, 2.4, 4}), "no measurable difference (1.61×, 95 % CI 0.80–2.40)");
    EXPECT_EQ(describeSpeedup({1.5, std::nan(""), std::nan(""), 1}), "1.50× (no interval: fewer than 4 timed pairs)");
    EXPECT_EQ(describeSpeedup({std::nan(""), std::nan(""), std::nan(""), 0}), "–");
    EXPECT_EQ(intervalText({1.18, 1.104, 1.266, 10}), "1.10–1.27");
}

TEST(SpeedupInterval, RelativeHalfWidth) {
    EXPECT_NEAR((SpeedupInterval{2.0, 1.9, 2.1, 10}.relativeHalfWidth()), 0.05, 1e-12);  // ±0.1 around 2
    EXPECT_TRUE(std::isinf((SpeedupInterval{2.0, std::nan(""), std::nan(""), 1}.relativeHalfWidth())));
}

TEST(SpeedupInterval, UnusableTimesGiveNoSpeedup) {
    EXPECT_TRUE(std::isnan(bootstrapSpeedup(std::vector<double>{}, std::vector<double>{}).speedup));
    EXPECT_TRUE(std::isnan(bootstrapSpeedup(std::vector<double>{1, 0}, std::vector<double>{1, 1}).speedup));
    const SpeedupInterval one = bootstrapSpeedup(std::vector<double>{10}, std::vector<double>{5});
    EXPECT_DOUBLE_EQ(one.speedup, 2.0);
    EXPECT_FALSE(one.known());
    // Three pairs are still too few for an interval; four are enough.
    EXPECT_FALSE(bootstrapSpeedup(std::vector<double>{10, 11, 12}, std::vector<double>{5, 6, 5}).known());
    EXPECT_TRUE(bootstrapSpeedup(std::vector<double>{10, 11, 12, 10}, std::vector<double>{5, 6, 5, 6}).known());
    // Extra elements of the longer series are ignored, not paired with nothing.
    EXPECT_EQ(bootstrapSpeedup(std::vector<double>{10, 10, 10, 10, 10}, std::vector<double>{5, 5, 5, 5}).pairs, 4);
}

}  // namespace
}  // namespace raycache
