#pragma once
// A rate over the last second or so: fed a running total (samples traced,
// frames shown) with the time it was read, it gives the total's growth per
// second over the readings of the last `windowSeconds`.
#include <chrono>
#include <deque>

namespace raycache {

class RateMeter {
public:
    using Clock = std::chrono::steady_clock;
    explicit RateMeter(double windowSeconds = 1.0) : window_(windowSeconds) {}

    void add(Clock::time_point when, double total);
    // Per second; 0 until two readings lie apart in time.
    double rate() const;
    void clear() { readings_.clear(); }

private:
    struct Reading {
        Clock::time_point when;
        double total;
    };
    double window_;
    std::deque<Reading> readings_;
};

}  // namespace raycache
