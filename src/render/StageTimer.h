#pragma once
// Adds the time until it goes out of scope to one stage's total
// (render/FrameStats.h StageTimes), when stage timing is on: it costs two
// clock reads per stage and wave, so it is off unless a profile is wanted.
#include <chrono>

namespace raycache {

class StageTimer {
public:
    using Clock = std::chrono::steady_clock;
    StageTimer(bool enabled, double& milliseconds)
        : target_(enabled ? &milliseconds : nullptr), start_(enabled ? Clock::now() : Clock::time_point{}) {}
    ~StageTimer() {
        if (target_) *target_ += std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
    }
    StageTimer(const StageTimer&) = delete;
    StageTimer& operator=(const StageTimer&) = delete;

private:
    double* target_;
    Clock::time_point start_;
};

}  // namespace raycache
