#pragma once
// When interleaved timing has run long enough: every variant's speed-up over
// the baseline (variant 0) known to ±5 % (95 % interval), or a cap on rounds
// or time reached. A pure function of the times so far, so it can be tested
// on made-up data and the runner stays a plain loop.
#include <string>
#include <vector>

#include "bench/InterleavedRuns.h"
#include "bench/SpeedupInterval.h"

namespace raycache {

struct AdaptiveSettings {
    int minRounds = 5;              // timed rounds always run
    int maxRounds = 5;              // never more; == minRounds times a fixed count
    double timeCapSeconds = 0.0;    // no new round once the timed rounds took this long; 0 = no cap
    double targetHalfWidth = 0.05;  // relative half-width of every interval, 0.05 = ±5 %
    BootstrapSettings bootstrap;
};

enum class StopReason {
    KeepGoing,  // run another round
    Precise,    // every interval within the target
    RoundCap,   // maxRounds reached first
    TimeCap,    // timeCapSeconds reached first
};

// "precise", "round cap", "time cap" ("running" for KeepGoing).
std::string toString(StopReason reason);

// After `times` (one entry per variant, all with the same number of timed
// rounds) and `elapsedSeconds` of timed rounds: stop or go on. Below
// minRounds: KeepGoing; then Precise before RoundCap before TimeCap.
StopReason adaptiveStop(const std::vector<VariantTimes>& times, const AdaptiveSettings& settings,
                        double elapsedSeconds);

}  // namespace raycache
