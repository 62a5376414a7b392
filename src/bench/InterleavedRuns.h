#pragma once
// Timing several variants of a job side by side: after warm-up, the variants
// run in turn (A B C A B C ...) so that machine noise hits them alike, and
// each variant's times are summarized by median and range. The adaptive
// form repeats rounds until the speed-ups are known precisely enough.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace raycache {

struct Variant {
    std::string name;
    // Runs the job once; returns the work done (e.g. rays traced), reported as-is.
    std::function<std::uint64_t()> run;
    // Optional, untimed, before every run (e.g. emptying caches).
    std::function<void()> prepare = {};
    // Optional, untimed, after every run (e.g. recording per-frame results, progress).
    std::function<void()> finish = {};
};

struct VariantTimes {
    std::string name;
    std::vector<double> milliseconds;  // one per timed run, in run order
    std::vector<double> warmupMilliseconds;  // the untimed warm-up runs, for the record
    std::uint64_t work = 0;            // from the last run
    double median() const;
    double min() const;
    double max() const;
};

std::vector<VariantTimes> runInterleaved(const std::vector<Variant>& variants, int warmupRounds, int timedRounds);

struct AdaptiveSettings;
enum class StopReason;

struct AdaptiveRun {
    std::vector<VariantTimes> times;
    int rounds = 0;              // timed rounds run
    double seconds = 0.0;        // wall time of the timed rounds
    StopReason reason{};         // why it stopped (AdaptiveStopping.h)
};

// Warm-up rounds, then timed rounds until adaptiveStop() says stop.
AdaptiveRun runInterleavedAdaptive(const std::vector<Variant>& variants, int warmupRounds,
                                   const AdaptiveSettings& settings);

}  // namespace raycache
