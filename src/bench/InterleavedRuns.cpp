#include "bench/InterleavedRuns.h"

#include "bench/AdaptiveStopping.h"
#include "core/SampleSummary.h"

#include <algorithm>
#include <chrono>

namespace raycache {

double VariantTimes::median() const { return summarize(milliseconds).median; }
double VariantTimes::min() const { return summarize(milliseconds).min; }
double VariantTimes::max() const { return summarize(milliseconds).max; }

namespace {

std::vector<VariantTimes> named(const std::vector<Variant>& variants) {
    std::vector<VariantTimes> times(variants.size());
    for (std::size_t i = 0; i < variants.size(); ++i) times[i].name = variants[i].name;
    return times;
}

void runRound(const std::vector<Variant>& variants, std::vector<VariantTimes>& times, bool timed) {
    for (std::size_t i = 0; i < variants.size(); ++i) {
        if (variants[i].prepare) variants[i].prepare();
        const auto start = std::chrono::steady_clock::now();
        times[i].work = variants[i].run();
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        (timed ? times[i].milliseconds : times[i].warmupMilliseconds).push_back(ms);
        if (variants[i].finish) variants[i].finish();
    }
}

}  // namespace

std::vector<VariantTimes> runInterleaved(const std::vector<Variant>& variants, int warmupRounds, int timedRounds) {
    std::vector<VariantTimes> times = named(variants);
    for (int round = 0; round < warmupRounds + timedRounds; ++round) runRound(variants, times, round >= warmupRounds);
    return times;
}

AdaptiveRun runInterleavedAdaptive(const std::vector<Variant>& variants, int warmupRounds,
                                   const AdaptiveSettings& settings) {
    AdaptiveRun run;
    run.times = named(variants);
    for (int round = 0; round < warmupRounds; ++round) runRound(variants, run.times, false);
    const auto start = std::chrono::steady_clock::now();
    for (;;) {
        run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        run.reason = adaptiveStop(run.times, settings, run.seconds);
        if (run.reason != StopReason::KeepGoing) break;
        runRound(variants, run.times, true);
        ++run.rounds;
    }
    return run;
}

}  // namespace raycache
