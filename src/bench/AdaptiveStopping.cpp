#include "bench/AdaptiveStopping.h"

#include <algorithm>

namespace raycache {

std::string toString(StopReason reason) {
    switch (reason) {
        case StopReason::KeepGoing:
            return "running";
        case StopReason::Precise:
            return "precise";
        case StopReason::RoundCap:
            return "round cap";
        case StopReason::TimeCap:
            return "time cap";
    }
    return "?";
}

StopReason adaptiveStop(const std::vector<VariantTimes>& times, const AdaptiveSettings& settings,
                        double elapsedSeconds) {
    if (times.empty()) return StopReason::Precise;
    const int rounds = static_cast<int>(times.front().milliseconds.size());
    if (rounds < settings.minRounds) return StopReason::KeepGoing;
    bool precise = true;
    for (std::size_t i = 1; i < times.size() && precise; ++i) {
        const SpeedupInterval s =
            bootstrapSpeedup(times.front().milliseconds, times[i].milliseconds, settings.bootstrap);
        precise = s.known() && s.relativeHalfWidth() <= settings.targetHalfWidth;
    }
    if (precise) return StopReason::Precise;
    if (rounds >= std::max(settings.minRounds, settings.maxRounds)) return StopReason::RoundCap;
    if (settings.timeCapSeconds > 0.0 && elapsedSeconds >= settings.timeCapSeconds) return StopReason::TimeCap;
    return StopReason::KeepGoing;
}

}  // namespace raycache
