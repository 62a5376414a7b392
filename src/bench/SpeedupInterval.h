#pragma once
// A speed-up measured with its uncertainty: baseline time / variant time with
// a 95 % confidence interval from a paired bootstrap over interleaved runs.
// Runs are paired by round (round i of both ran back to back, so they shared
// the machine's state); resampling whole rounds keeps that pairing. A fixed
// seed makes the interval, and so every report, reproducible from the times.
#include <cstdint>
#include <span>
#include <string>

namespace raycache {

// Fewer pairs give no interval: a bootstrap of 2 or 3 values only reshuffles
// them and yields intervals far narrower than the truth.
inline constexpr int kMinPairsForInterval = 4;

struct SpeedupInterval {
    double speedup = 0.0;  // on all the data; NaN when it cannot be computed
    double low = 0.0;      // 2.5th percentile of the bootstrap distribution
    double high = 0.0;     // 97.5th percentile
    int pairs = 0;         // paired samples it rests on

    bool known() const;
    // The interval contains 1.0: the data cannot tell the variant from the baseline.
    bool containsOne() const;
    // Half the interval's width relative to the speed-up (0.05 = ±5 %); infinite when unknown.
    double relativeHalfWidth() const;
};

// How a set of times becomes one time per variant.
enum class TimeStatistic {
    Median,  // still camera: every frame renders the same view, the median resists outliers
    Mean,    // camera path: frames differ by design, the total (mean) is what a user waits for
};

struct BootstrapSettings {
    int resamples = 2000;
    std::uint64_t seed = 0x5eed'2026;
    double confidence = 0.95;
    TimeStatistic statistic = TimeStatistic::Median;
};

// Speed-up of `variantMs` over `baselineMs` (statistic(baseline) / statistic(variant)).
// Pairs element i of both; extra elements of the longer one are ignored.
// Fewer than kMinPairsForInterval pairs: the speed-up without an interval;
// no pairs or a non-positive or non-finite time: all NaN.
SpeedupInterval bootstrapSpeedup(std::span<const double> baselineMs, std::span<const double> variantMs,
                                 const BootstrapSettings& settings = {});

// "1.18× (95 % CI 1.10–1.27)", or "no measurable difference (0.97×, 95 % CI 0.91–1.05)"
// when the interval contains 1.0, or "–" when unknown.
std::string describeSpeedup(const SpeedupInterval& s);
// Table cell: "1.18× (1.10–1.27)", "1.18×" without an interval,
// "no measurable difference (0.97×, 0.91–1.05)" when the interval contains 1,
// "–" when there is no speed-up.
std::string speedupCell(const SpeedupInterval& s);
// The interval alone, "1.10–1.27", for table cells; "–" when unknown.
std::string intervalText(const SpeedupInterval& s);

}  // namespace raycache
