#pragma once
// The viewer's render thread: owns the caches, renders what the newest
// RenderRequest asks for, and hands each finished frame to the UI thread
// through a FrameHandoff. The UI thread never waits for a render.
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "cache/RayCache.h"
#include "core/DisplayTransform.h"
#include "core/Image.h"
#include "core/Parallel.h"
#include "render/RenderSettings.h"
#include "scene/CameraPath.h"
#include "scene/Scene.h"
#include "session/FrameLoop.h"
#include "session/RenderSession.h"
#include "trace/TraceScene.h"
#include "rendercache/AsyncRenderCache.h"
#include "viewer/FrameHandoff.h"
#include "viewer/ProgressiveFilm.h"
#include "viewer/RateMeter.h"
#include "viewer/RenderRequest.h"
#include "viewer/Srgb8Encoder.h"

namespace raycache {

struct RenderWorkerSetup {
    const Scene* scene = nullptr;         // outlives the worker
    const TraceScene* tracer = nullptr;   // outlives the worker
    CameraPath path;
    FrameTimeline timeline;               // scripted runs: the moment each path frame shows
    RenderSettings base;                  // threads, min weight, command-line cache overrides
    // Scripted run: render path frames 0 .. frames-1 exactly once each, every
    // one handed over (lossless), then stop. Empty: interactive.
    std::optional<int> scriptedFrames;
    std::function<void()> onPublished;    // called after each handed-over frame (wakes the UI loop)
    // The threads the async Render Cache's tracer takes (0: half of
    // `base.threads`) and its display (0: all), see splitRenderCacheThreads
    // (RenderRequest::renderCacheAsync asks for that mode).
    int renderCacheTraceThreads = 0;
    int renderCacheDisplayThreads = 0;
    double renderCacheRequestFrames = 2.0;  // AsyncRenderCache::setRequestFrames
    double renderCacheReshadeMs = 0.0;      // AsyncRenderCache::setReshadeBudgetMs
    DisplaySettings display;                // exposure and view transform of the shown frames
    // `--spp N`: a still view's full frames (ray pipeline) are refined to N
    // samples per pixel, one sample layer a frame (ProgressiveFilm); 1: off.
    int samplesPerPixel = 1;
};

class RenderWorker {
public:
    // Starts the thread; it waits for the first request.
    RenderWorker(RenderWorkerSetup setup, FrameHandoff& handoff);
    // Stops and joins the thread (a frame in flight is finished first).
    ~RenderWorker();
    RenderWorker(const RenderWorker&) = delete;
    RenderWorker& operator=(const RenderWorker&) = delete;

    // Replaces the pending request. Never waits for a render.
    void submit(const RenderRequest& request);
    // True once a scripted run has handed over its last frame, or the thread
    // stopped on an error.
    bool finished() const;
    // What stopped the thread, if it failed (rethrow on the UI thread).
    std::exception_ptr error() const;

private:
    void run();
    void renderOne(const RenderRequest& request, DisplayFrame& frame);
    void applyConfig(const ViewerRenderConfig& config, DisplayFrame& frame);
    // `display`: how the image's light is shown (null: the values as they are).
    void encode(const Image& film, std::vector<std::uint8_t>& rgba, const DisplayTransform* display = nullptr) const;
    // The async Render Cache's display frame; makes the pair anew when the size changed.
    void reconstructAsync(const RenderRequest& request, const Camera& camera, DisplayFrame& frame);
    // Makes the frame the request asks for into film_ and frame.stats (the
    // configured pipeline; under auto, a full frame or the Render Cache).
    void renderFrame(const RenderRequest& request, const Camera& camera, DisplayFrame& frame);
    // A frame of the session's own pipeline, the async Render Cache's tracer
    // kept out of the caches meanwhile (auto keeps it between its turns).
    void renderSessionFrame(const RenderRequest& request, const Camera& camera, DisplayFrame& frame);
    // Whether the session's frame for `request` is refined (ProgressiveFilm):
    // --spp above 1, the ray pipeline, no overlay that needs a plain frame.
    bool refines(const RenderRequest& request) const;
    // The next frame of a still view's refinement into film_: the plain
    // frame when the view is new, then one sample layer a frame, then
    // nothing more to do once complete.
    void refineFrame(const RenderRequest& request, const Camera& camera, DisplayFrame& frame);
    // The Render Cache's maps of the frame just made, if it made any.
    const RenderCacheOverlays* shownOverlays(const DisplayFrame& frame) const;

    RenderWorkerSetup setup_;
    FrameHandoff& handoff_;
    Parallel parallel_;
    Srgb8Encoder encoder_;
    DisplayTransform display_;

    // Render-thread state.
    std::optional<ViewerRenderConfig> config_;  // in use; empty before the first frame
    RenderSettings settings_;
    std::unique_ptr<RenderSession> session_;   // the configured pipeline and caches
    std::unique_ptr<RenderSession> uncached_;  // the same without caches, for the difference view
    // Pipeline auto, synchronous Render Cache: its own session (and caches),
    // sharing the tracer and threads; made when first shown.
    std::unique_ptr<RenderSession> renderCacheSession_;
    bool showsAsync_ = false;  // the last frame was the async Render Cache's
    std::string configError_;
    std::uint64_t clearCount_ = 0;
    std::uint64_t pathRestartCount_ = 0;
    int pathFrame_ = 0;
    std::uint64_t serial_ = 0;
    Image film_;
    Image uncachedFilm_;
    std::vector<std::uint8_t> uncachedRgba_;
    RateMeter displayRate_, sampleRate_, batchRate_, requestRate_, busyRate_;
    std::int64_t displayFrames_ = 0;
    std::int64_t lastMerged_ = 0;
    // --spp: what shapes the refined view's image; a change starts it again.
    struct RefinedView {
        Camera camera;
        int width = 0, height = 0;
        ViewerRenderConfig config;
        float time = 0.0f;
        std::uint64_t clearCount = 0;
        bool operator==(const RefinedView&) const = default;
    };
    std::optional<ProgressiveFilm> refinement_;  // set when setup_.samplesPerPixel > 1
    std::optional<RefinedView> refinedView_;
    Image layer_;
    float frameTime_ = 0.0f;         // the moment the frame being made shows (0 for a still scene)
    // The last frame was a complete refinement: nothing left to render until
    // the request changes (read by the wait's predicate, on this thread).
    bool refinementComplete_ = false;

    // Shared with the UI thread.
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::optional<RenderRequest> request_;
    std::uint64_t requestSerial_ = 0;  // bumped when the request changes
    bool stop_ = false;
    bool finished_ = false;
    bool samplesArrived_ = false;  // the async Render Cache's tracer handed over a batch
    std::exception_ptr error_;

    // Render-thread state, after the mutex: its tracer thread wakes this one
    // through it until it is destroyed (joined).
    std::unique_ptr<AsyncRenderCache> async_;

    std::thread thread_;  // last: starts after everything above exists
};

}  // namespace raycache
