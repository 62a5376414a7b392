#pragma once
// The Render Cache displayed at its own rate (rendercache/AsyncRenderCache.h),
// measured without a window: display frames along a scene's camera path,
// each reconstructed for the next camera as soon as the last one is done,
// while the tracer feeds samples. What `raycache view` does under
// `--pipeline render-cache` but the 8-bit encoding, the upload and the
// present (the viewer's scripted runs report those apart:
// benchmarks/render_cache_async_speed.sh).
#include "rendercache/AsyncRenderCache.h"

namespace raycache {

struct AsyncDisplayResult {
    int displayFrames = 0;            // timed: after the first, whose request traces every pixel
    double displayFps = 0.0;          // display frames per second of wall time
    double samplesPerSecond = 0.0;    // camera rays the tracer traced, over the same time
    double medianReconstructionMs = 0.0;
    double medianReshadeMs = 0.0;
    int lastReshadeInterval = 1;      // reshading's interval at the end (rendercache/ReshadeBudget.h)
};

// `frames` display frames after the first along scene.cameraPath, threads
// split as the viewer splits them; `reshadeBudgetMs` as
// AsyncRenderCache::setReshadeBudgetMs. `cache` may be null.
AsyncDisplayResult measureAsyncDisplay(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                                       RayCache* cache, int frames, double reshadeBudgetMs);

}  // namespace raycache
