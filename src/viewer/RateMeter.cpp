#include "viewer/RateMeter.h"

namespace raycache {

void RateMeter::add(Clock::time_point when, double total) {
    readings_.push_back({when, total});
    // Keep one reading at or before the window's start, so the rate spans
    // the whole window even when readings are sparse.
    while (readings_.size() > 2 &&
           std::chrono::duration<double>(when - readings_[1].when).count() >= window_)
        readings_.pop_front();
}

double RateMeter::rate() const {
    if (readings_.size() < 2) return 0.0;
    const double seconds = std::chrono::duration<double>(readings_.back().when - readings_.front().when).count();
    return seconds > 0.0 ? (readings_.back().total - readings_.front().total) / seconds : 0.0;
}

}  // namespace raycache
