#include "viewer/FrameHandoff.h"

#include <utility>

namespace raycache {

bool FrameHandoff::publish(DisplayFrame& frame, bool lossless) {
    std::unique_lock lock(mutex_);
    if (lossless) taken_.wait(lock, [&] { return !hasReady_ || closed_; });
    if (closed_) return false;
    std::swap(ready_, frame);
    hasReady_ = true;
    return true;
}

bool FrameHandoff::take(DisplayFrame& frame) {
    {
        std::lock_guard lock(mutex_);
        if (!hasReady_) return false;
        std::swap(ready_, frame);
        hasReady_ = false;
    }
    taken_.notify_all();
    return true;
}

void FrameHandoff::close() {
    {
        std::lock_guard lock(mutex_);
        closed_ = true;
    }
    taken_.notify_all();
}

}  // namespace raycache
