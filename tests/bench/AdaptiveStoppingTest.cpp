#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "bench/AdaptiveStopping.h"
#include "bench/InterleavedRuns.h"

namespace raycache {
namespace {

// `rounds` rounds of a baseline and one variant: baseline ~ 20 ms, variant ~ 10 ms,
// each with uniform noise of ±noise ms.
std::vector<VariantTimes> times(int rounds, double noise, unsigned seed = 1) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-noise, noise);
    std::vector<VariantTimes> t(2);
    for (int i = 0; i < rounds; ++i) {
        t[0].milliseconds.push_back(20.0 + u(rng));
        t[1].milliseconds.push_back(10.0 + u(rng));
    }
    return t;
}

AdaptiveSettings settings(int minRounds, int maxRounds, double capSeconds) {
    AdaptiveSettings s;
    s.minRounds = minRounds;
    s.maxRounds = maxRounds;
    s.timeCapSeconds = capSeconds;
    return s;
}

TEST(AdaptiveStopping, AlwaysRunsTheMinimumRounds) {
    // Even perfectly precise data and an exhausted time cap.
    EXPECT_EQ(adaptiveStop(times(3, 0.0), settings(4, 10, 1.0), 100.0), StopReason::KeepGoing);
}

TEST(AdaptiveStopping, StopsAsSoonAsEveryIntervalIsWithinFivePercent) {
    // ±0.1 ms on 10 ms: the speed-up 2 is known to far better than ±5 %.
    EXPECT_EQ(adaptiveStop(times(5, 0.1), settings(5, 50, 0.0), 1.0), StopReason::Precise);
}

TEST(AdaptiveStopping, NoisyDataKeepsGoingUntilACap) {
    // ±9 ms on 10 ms and 20 ms: 6 rounds cannot pin the ratio to ±5 %.
    const std::vector<VariantTimes> noisy = times(6, 9.0);
    EXPECT_EQ(adaptiveStop(noisy, settings(5, 50, 10.0), 2.0), StopReason::KeepGoing);
    EXPECT_EQ(adaptiveStop(noisy, settings(5, 50, 10.0), 10.0), StopReason::TimeCap);
    EXPECT_EQ(adaptiveStop(noisy, settings(5, 6, 10.0), 2.0), StopReason::RoundCap);
    EXPECT_EQ(adaptiveStop(noisy, settings(5, 50, 0.0), 1e9), StopReason::KeepGoing);  // 0 = no time cap
}

TEST(AdaptiveStopping, MoreRoundsNarrowTheIntervalUntilItIsPrecise) {
    // The same noise: imprecise at 6 rounds, precise with enough of them.
    const AdaptiveSettings s = settings(5, 1000, 0.0);
    int rounds = 6;
    while (rounds < 1000 && adaptiveStop(times(rounds, 3.0, 5), s, 0.0) == StopReason::KeepGoing) rounds += 5;
    EXPECT_GT(rounds, 6);
    EXPECT_LT(rounds, 1000);
    EXPECT_EQ(adaptiveStop(times(rounds, 3.0, 5), s, 0.0), StopReason::Precise);
}

TEST(AdaptiveStopping, EveryVariantMustBePrecise) {
    std::vector<VariantTimes> t = times(8, 0.1);
    VariantTimes noisy;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(1.0, 30.0);
    for (int i = 0; i < 8; ++i) noisy.milliseconds.push_back(u(rng));
    t.push_back(noisy);
    EXPECT_EQ(adaptiveStop(t, settings(5, 50, 0.0), 0.0), StopReason::KeepGoing);
}

TEST(AdaptiveStopping, FixedCountWhenMaxEqualsMin) {
    EXPECT_EQ(adaptiveStop(times(4, 9.0), settings(4, 4, 0.0), 0.0), StopReason::RoundCap);
}

TEST(AdaptiveStopping, RunnerDoesWarmupThenTheRoundsTheRuleAsksFor) {
    int runsA = 0, runsB = 0, prepared = 0;
    const std::vector<Variant> variants = {
        {"a", [&] { return static_cast<std::uint64_t>(++runsA); }},
        {"b", [&] { return static_cast<std::uint64_t>(++runsB); }, [&] { ++prepared; }}};
    const AdaptiveRun run = runInterleavedAdaptive(variants, 2, settings(3, 3, 0.0));
    EXPECT_EQ(run.rounds, 3);
    EXPECT_EQ(runsA, 5);
    EXPECT_EQ(runsB, 5);
    EXPECT_EQ(prepared, 5);
    ASSERT_EQ(run.times.size(), 2u);
    EXPECT_EQ(run.times[1].milliseconds.size(), 3u);
    EXPECT_EQ(run.times[1].warmupMilliseconds.size(), 2u);
    EXPECT_EQ(run.times[1].work, 5u);
    EXPECT_NE(run.reason, StopReason::KeepGoing);
}

TEST(AdaptiveStopping, ReasonsHaveNames) {
    EXPECT_EQ(toString(StopReason::Precise), "precise");
    EXPECT_EQ(toString(StopReason::RoundCap), "round cap");
    EXPECT_EQ(toString(StopReason::TimeCap), "time cap");
}

}  // namespace
}  // namespace raycache
