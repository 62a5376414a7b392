#include "bench/InterleavedRuns.h"

#include <algorithm>
#include <chrono>

namespace raycache {

double VariantTimes::median() const {
    std::vector<double> v = milliseconds;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    if (n == 0) return 0.0;
    return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
double VariantTimes::min() const { return *std::min_element(milliseconds.begin(), milliseconds.end()); }
double VariantTimes::max() const { return *std::max_element(milliseconds.begin(), milliseconds.end()); }

std::vector<VariantTimes> runInterleaved(const std::vector<Variant>& variants, int warmupRounds, int timedRounds) {
    std::vector<VariantTimes> times(variants.size());
    for (std::size_t i = 0; i < variants.size(); ++i) times[i].name = variants[i].name;
    for (int round = 0; round < warmupRounds + timedRounds; ++round) {
        for (std::size_t i = 0; i < variants.size(); ++i) {
            if (variants[i].prepare) variants[i].prepare();
            const auto start = std::chrono::steady_clock::now();
            times[i].work = variants[i].run();
            const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            if (round >= warmupRounds) times[i].milliseconds.push_back(ms);
        }
    }
    return times;
}

}  // namespace raycache
