#include "bench/SpeedupInterval.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "core/TextFormat.h"

namespace raycache {

namespace {

double statistic(std::vector<double>& v, TimeStatistic s) {
    if (s == TimeStatistic::Mean) {
        double sum = 0.0;
        for (double x : v) sum += x;
        return sum / static_cast<double>(v.size());
    }
    const std::size_t n = v.size(), mid = n / 2;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
    if (n % 2 == 1) return v[mid];
    const double upper = v[mid];
    const double lower = *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid));
    return 0.5 * (lower + upper);
}

// Linear interpolation between order statistics of a sorted sample.
double percentile(const std::vector<double>& sorted, double q) {
    const double pos = q * static_cast<double>(sorted.size() - 1);
    const auto i = static_cast<std::size_t>(std::floor(pos));
    const std::size_t j = std::min(i + 1, sorted.size() - 1);
    return sorted[i] + (pos - static_cast<double>(i)) * (sorted[j] - sorted[i]);
}

}  // namespace

bool SpeedupInterval::known() const {
    return pairs >= kMinPairsForInterval && std::isfinite(speedup) && std::isfinite(low) && std::isfinite(high);
}

bool SpeedupInterval::containsOne() const {
    return known() && low <= 1.0 && 1.0 <= high;
}

double SpeedupInterval::relativeHalfWidth() const {
    if (!known() || speedup <= 0.0) return INFINITY;
    return 0.5 * (high - low) / speedup;
}

SpeedupInterval bootstrapSpeedup(std::span<const double> baselineMs, std::span<const double> variantMs,
                                 const BootstrapSettings& settings) {
    const double nan = std::nan("");
    SpeedupInterval out{nan, nan, nan, 0};
    const std::size_t n = std::min(baselineMs.size(), variantMs.size());
    for (std::size_t i = 0; i < n; ++i)
        if (!(baselineMs[i] > 0.0) || !(variantMs[i] > 0.0) || !std::isfinite(baselineMs[i]) ||
            !std::isfinite(variantMs[i]))
            return out;
    if (n == 0) return out;
    out.pairs = static_cast<int>(n);
    std::vector<double> b(baselineMs.begin(), baselineMs.begin() + static_cast<std::ptrdiff_t>(n));
    std::vector<double> v(variantMs.begin(), variantMs.begin() + static_cast<std::ptrdiff_t>(n));
    out.speedup = statistic(b, settings.statistic) / statistic(v, settings.statistic);
    if (static_cast<int>(n) < kMinPairsForInterval) return out;

    // std::mt19937_64 is specified bit for bit; the index is drawn with our own
    // mapping because uniform_int_distribution differs between libraries.
    std::mt19937_64 rng(settings.seed);
    std::vector<double> ratios(static_cast<std::size_t>(std::max(1, settings.resamples)));
    for (double& r : ratios) {
        for (std::size_t k = 0; k < n; ++k) {
            const std::size_t i = static_cast<std::size_t>(rng() % n);
            b[k] = baselineMs[i];
            v[k] = variantMs[i];
        }
        r = statistic(b, settings.statistic) / statistic(v, settings.statistic);
    }
    std::sort(ratios.begin(), ratios.end());
    const double tail = 0.5 * (1.0 - settings.confidence);
    out.low = percentile(ratios, tail);
    out.high = percentile(ratios, 1.0 - tail);
    return out;
}

std::string intervalText(const SpeedupInterval& s) {
    if (!s.known()) return "–";
    return formatFixed(s.low, 2) + "–" + formatFixed(s.high, 2);
}

std::string describeSpeedup(const SpeedupInterval& s) {
    if (!std::isfinite(s.speedup)) return "–";
    if (!s.known())
        return formatFixed(s.speedup, 2) + "× (no interval: fewer than " + std::to_string(kMinPairsForInterval) +
               " timed pairs)";
    const std::string ci = "95 % CI " + intervalText(s);
    if (s.containsOne()) return "no measurable difference (" + formatFixed(s.speedup, 2) + "×, " + ci + ")";
    return formatFixed(s.speedup, 2) + "× (" + ci + ")";
}

std::string speedupCell(const SpeedupInterval& s) {
    if (!std::isfinite(s.speedup)) return "–";
    if (!s.known()) return formatFixed(s.speedup, 2) + "×";
    if (s.containsOne()) return "no measurable difference (" + formatFixed(s.speedup, 2) + "×, " + intervalText(s) + ")";
    return formatFixed(s.speedup, 2) + "× (" + intervalText(s) + ")";
}

}  // namespace raycache
