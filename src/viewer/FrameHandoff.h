#pragma once
// Hands finished frames from the render thread to the UI thread. The
// producer fills its own DisplayFrame and swaps it in; the consumer swaps
// the newest one out; the three buffers circulate, so nothing is allocated
// per frame and neither side ever waits for the other's work (except in
// lossless mode, below).
#include <condition_variable>
#include <mutex>

#include "viewer/DisplayFrame.h"

namespace raycache {

class FrameHandoff {
public:
    // Producer: makes `frame` the newest frame and gives back a buffer to
    // fill next. A frame not yet taken is replaced, unless `lossless`, in
    // which case this waits until it is taken (scripted runs show every
    // frame). Returns false, publishing nothing, once closed.
    bool publish(DisplayFrame& frame, bool lossless);
    // Consumer: if a frame was published since the last take, swaps it into
    // `frame` and returns true; never waits.
    bool take(DisplayFrame& frame);
    // Wakes and refuses any publisher; for shutting down.
    void close();

private:
    std::mutex mutex_;
    std::condition_variable taken_;
    DisplayFrame ready_;
    bool hasReady_ = false;
    bool closed_ = false;
};

}  // namespace raycache
