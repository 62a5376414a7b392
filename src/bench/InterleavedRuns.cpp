#include "bench/InterleavedRuns.h"

#include "bench/SampleSummary.h"

#include <algorithm>
#include <chrono>

namespace raycache {

double VariantTimes::median() const { return summarize(milliseconds).median; }
double VariantTimes::min() const { return summarize(milliseconds).min; }
double VariantTimes::max() const { return summarize(milliseconds).max; }

std::vector<VariantTimes> runInterleaved(const std::vector<Variant>& variants, int warmupRounds, int timedRounds) {
    std::vector<VariantTimes> times(variants.size());
    for (std::size_t i = 0; i < variants.size(); ++i) times[i].name = variants[i].name;
    for (int round = 0; round < warmupRounds + timedRounds; ++round) {
        for (std::size_t i = 0; i < variants.size(); ++i) {
            if (variants[i].prepare) variants[i].prepare();
            const auto start = std::chrono::steady_clock::now();
            times[i].work = variants[i].run();
            const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            (round >= warmupRounds ? times[i].milliseconds : times[i].warmupMilliseconds).push_back(ms);
            if (variants[i].finish) variants[i].finish();
        }
    }
    return times;
}

}  // namespace raycache
