#pragma once
// The Render Cache displayed at its own rate (Walter et al. 1999's
// design): the display thread reconstructs an image for the newest camera
// as often as it can, while a tracer thread keeps tracing the samples the
// display's request maps ask for. Built on RenderCachePipeline's two
// halves (reconstruct(), traceSamples()).
//
// The protocol, one request in flight:
// - a display frame (reconstruct()) first merges the batches traced since
//   the last one; if the request it last issued has been traced and merged
//   to its end, it builds a new request map and issues it;
// - the tracer takes the request and traces it in batches of a few
//   thousand pixels, handing each over as soon as it is done (the image
//   fills in as they come); batches are visited in a spread order so that a
//   large request (a first frame) fills the whole image evenly;
// - samples age by one per request merged to its end, not per display
//   frame: a display faster than the tracer does not age samples out before
//   new ones come (as rendering one request per frame does in render()).
//
// A request asks for what the tracer traces in about `requestFrames`
// display frames (its measured rays per second times the display's
// reconstruction time; 2 by default), at least the settings' budget: a
// faster tracer gets more to do, instead of idling. 0 asks for the budget
// alone: the tracer then idles more and leaves the cores to the display.
//
// Images depend on timing: this mode is for the interactive viewer. Runs
// that must repeat (`raycache render`, `bench`, scripted viewer runs) use
// RenderCachePipeline::render().
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/Parallel.h"
#include "rendercache/RenderCachePipeline.h"

namespace raycache {

// How the threads are shared between the display and the tracer.
struct AsyncRenderCacheThreads {
    int display = 1;
    int trace = 1;
};

// `threads` (0: the machine's): the display reconstructs on `displayThreads`
// (0: all of them) and `traceThreads` trace (0: half, at least one), sharing
// the cores. oneTBB's one pool of workers serves both: the display's loops
// take the cores the tracer leaves (while it waits for a request, say). On
// two cores this beat one display and one trace thread in display rate and
// in samples per second alike (docs/viewer.md).
AsyncRenderCacheThreads splitRenderCacheThreads(int threads, int traceThreads = 0, int displayThreads = 0);

// What the tracer did since it started.
struct AsyncTraceCounts {
    std::int64_t requests = 0;   // requests traced to their end
    std::int64_t batches = 0;    // batches handed over
    std::int64_t samples = 0;    // camera rays traced (new samples)
    std::int64_t merged = 0;     // samples merged into the pool by display frames
    double busySeconds = 0.0;    // time spent tracing
};

class AsyncRenderCache {
public:
    // Starts the tracer thread, which waits for the first request.
    // `scene`, `tracer` and `cache` (may be null) must outlive this; the
    // scene must not move while it lives (its meshes are not refreshed).
    // `onSamples` (may be empty) is called on the tracer thread after each
    // batch is handed over and when the tracer stops on an error.
    AsyncRenderCache(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings, RayCache* cache,
                     AsyncRenderCacheThreads threads, std::function<void()> onSamples = {});
    // Stops the tracer after the batch it is tracing (dropped) and joins it.
    ~AsyncRenderCache();
    AsyncRenderCache(const AsyncRenderCache&) = delete;
    AsyncRenderCache& operator=(const AsyncRenderCache&) = delete;

    // Display thread: one display frame (see above) of `camera` into
    // `film`. Rethrows what stopped the tracer, if it failed.
    FrameStats reconstruct(const Camera& camera, Image& film);
    // Batches wait to be merged: the next display frame has something new.
    bool samplesWaiting() const;
    AsyncTraceCounts counts() const;
    // The maps of the last display frame (its request map empty on frames
    // that issued no request).
    const RenderCacheOverlays* overlays() const { return pipeline_.renderCacheOverlays(); }
    AsyncRenderCacheThreads threads() const { return threads_; }
    // Display thread: see above; >= 0.
    void setRequestFrames(double frames) { requestFrames_ = frames; }
    // Display thread: after each display frame whose camera moved, the
    // reshading interval is chosen to keep reshading within `ms` a frame
    // (rendercache/ReshadeBudget.h); 0 (the default) reshades every sample
    // every frame.
    void setReshadeBudgetMs(double ms) { reshadeBudgetMs_ = ms; }
    // The interval the next display frame reshades with.
    int reshadeInterval() const { return pipeline_.reshadeInterval(); }
    // Keeps the tracer out of the caches while held (it merges its stores
    // into them between batches): for reading them on another thread.
    std::unique_lock<std::mutex> holdCaches() { return std::unique_lock<std::mutex>(pipeline_.cacheMutex()); }

private:
    void traceLoop();
    // Traces `pixels` of `camera` in batches; false when told to stop.
    bool tracePart(const Camera& camera, const std::vector<PixelCoord>& pixels, bool endsRequest);

    AsyncRenderCacheThreads threads_;
    int pixels_;
    float minimumShare_;  // the settings' budget
    Parallel displayParallel_;
    Parallel traceParallel_;
    RenderCachePipeline pipeline_;
    std::function<void()> onSamples_;

    // Display thread only.
    bool requestOutstanding_ = false;  // issued, not yet merged to its end
    std::vector<SampleBatch> merging_;
    double reconstructSeconds_ = 0.0;  // the last display frame's
    double requestFrames_ = 2.0;
    double reshadeBudgetMs_ = 0.0;
    std::optional<Camera> lastCamera_;  // the last display frame's

    // Tracer thread only.
    std::vector<TileScratch> traceScratch_;

    // Shared, under mutex_.
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::optional<SampleRequest> request_;  // issued, not yet taken by the tracer
    std::vector<SampleBatch> ready_;        // traced, not yet merged
    AsyncTraceCounts counts_;
    bool stop_ = false;
    std::exception_ptr error_;

    std::thread thread_;  // last: starts after everything above exists
};

}  // namespace raycache
