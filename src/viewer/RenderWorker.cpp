#include "viewer/RenderWorker.h"

#include <algorithm>
#include <bit>
#include <chrono>

#include "core/Elapsed.h"
#include "core/Errors.h"
#include "render/FramePipeline.h"
#include "viewer/CacheLevelOverlayImage.h"
#include "viewer/CubeInspectorImage.h"
#include "viewer/DifferenceHeatMap.h"
#include "viewer/PipelineChoice.h"
#include "viewer/RenderCacheOverlayImage.h"

namespace raycache {

RenderWorker::RenderWorker(RenderWorkerSetup setup, FrameHandoff& handoff)
    : setup_(std::move(setup)), handoff_(handoff), parallel_(setup_.base.threads), display_(setup_.display),
      settings_(setup_.base),
      refinement_(setup_.samplesPerPixel > 1 ? std::optional<ProgressiveFilm>(setup_.samplesPerPixel) : std::nullopt),
      thread_([this] { run(); }) {}

RenderWorker::~RenderWorker() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    handoff_.close();  // a lossless publish may be waiting for the UI
    thread_.join();
}

void RenderWorker::submit(const RenderRequest& request) {
    {
        std::lock_guard lock(mutex_);
        if (request_ && *request_ == request) return;
        request_ = request;
        ++requestSerial_;
    }
    wake_.notify_all();
}

bool RenderWorker::finished() const {
    std::lock_guard lock(mutex_);
    return finished_;
}

std::exception_ptr RenderWorker::error() const {
    std::lock_guard lock(mutex_);
    return error_;
}

void RenderWorker::run() {
    DisplayFrame frame;
    std::uint64_t renderedSerial = 0;
    try {
        for (;;) {
            RenderRequest request;
            {
                std::unique_lock lock(mutex_);
                // Render again when the request changed, or when asked to keep
                // going: the async Render Cache then when new samples came
                // (without them its image would not change); not once a
                // refined still view is complete (nothing would change).
                wake_.wait(lock, [&] {
                    const bool keepGoing = request_ && request_->continuous && !refinementComplete_ &&
                                           (showsAsync_ ? samplesArrived_ : true);
                    return stop_ || (request_ && (requestSerial_ != renderedSerial || keepGoing ||
                                                  request_->playPath || setup_.scriptedFrames));
                });
                if (stop_) return;
                request = *request_;
                renderedSerial = requestSerial_;
            }
            if (setup_.scriptedFrames) request.playPath = true;
            renderOne(request, frame);
            if (!handoff_.publish(frame, setup_.scriptedFrames.has_value())) return;
            if (setup_.onPublished) setup_.onPublished();
            if (setup_.scriptedFrames && pathFrame_ >= *setup_.scriptedFrames) {
                std::lock_guard lock(mutex_);
                finished_ = true;
                break;
            }
        }
    } catch (...) {
        std::lock_guard lock(mutex_);
        error_ = std::current_exception();
        finished_ = true;
    }
    async_.reset();  // joins its tracer (a batch in flight is finished first)
    if (setup_.onPublished) setup_.onPublished();  // let the UI see finished_/error_
}

void RenderWorker::applyConfig(const ViewerRenderConfig& config, DisplayFrame&) {
    if (config_ && *config_ == config) return;
    const std::string error = viewerRenderConfigError(*setup_.scene, setup_.base, config);
    if (!error.empty()) {
        configError_ = error;
        if (config_) return;  // keep rendering with the last good config
        throw InputError(error);
    }
    configError_.clear();
    config_ = config;
    settings_ = applyViewerRenderConfig(setup_.base, config);
    async_.reset();    // its tracer uses the session's caches
    renderCacheSession_.reset();
    session_.reset();  // free the old cubes before allocating the new ones
    RenderSettings uncached = settings_;
    uncached.cache.techniqueOverride = CacheTechnique::None;
    if (setup_.scene->animation.empty()) {
        session_ = std::make_unique<RenderSession>(*setup_.scene, settings_, *setup_.tracer, parallel_);
        uncached_ = std::make_unique<RenderSession>(*setup_.scene, uncached, *setup_.tracer, parallel_);
    } else {
        // A session that animates moves its tracer: each needs its own.
        session_ = std::make_unique<RenderSession>(*setup_.scene, settings_);
        uncached_ = std::make_unique<RenderSession>(*setup_.scene, uncached);
    }
}

void RenderWorker::encode(const Image& film, std::vector<std::uint8_t>& rgba, const DisplayTransform* display) const {
    rgba.resize(static_cast<std::size_t>(film.width()) * static_cast<std::size_t>(film.height()) * 4);
    constexpr int kRowsPerTask = 8;
    const int tasks = (film.height() + kRowsPerTask - 1) / kRowsPerTask;
    parallel_.forEachIndex(tasks, [&](int task, int) {
        const int y0 = task * kRowsPerTask;
        encoder_.encodeRows(film, y0, std::min(y0 + kRowsPerTask, film.height()), rgba, display);
    });
}

void RenderWorker::reconstructAsync(const RenderRequest& request, const Camera& camera, DisplayFrame& frame) {
    if (async_ && (film_.width() != request.width || film_.height() != request.height)) async_.reset();
    if (!async_) {
        RenderSettings settings = settings_;
        settings.width = request.width;
        settings.height = request.height;
        const AsyncRenderCacheThreads threads = splitRenderCacheThreads(parallel_.threadCount(), setup_.renderCacheTraceThreads,
                                                                        setup_.renderCacheDisplayThreads);
        async_ = std::make_unique<AsyncRenderCache>(*setup_.scene, *setup_.tracer, settings, &session_->cache(), threads,
                                                    [this] {
                                                        {
                                                            std::lock_guard lock(mutex_);
                                                            samplesArrived_ = true;
                                                        }
                                                        wake_.notify_all();
                                                    });
        async_->setRequestFrames(setup_.renderCacheRequestFrames);
        async_->setReshadeBudgetMs(setup_.renderCacheReshadeMs);
        for (RateMeter* meter : {&displayRate_, &sampleRate_, &batchRate_, &requestRate_, &busyRate_}) meter->clear();
        lastMerged_ = 0;
        film_ = Image(request.width, request.height);
    }
    {
        // Batches that come while this frame is made wake the next one.
        std::lock_guard lock(mutex_);
        samplesArrived_ = false;
    }
    frame.reshadeInterval = async_->reshadeInterval();
    frame.stats = async_->reconstruct(camera, film_);
    const AsyncTraceCounts counts = async_->counts();
    const auto now = RateMeter::Clock::now();
    displayRate_.add(now, static_cast<double>(++displayFrames_));
    sampleRate_.add(now, static_cast<double>(counts.samples));
    batchRate_.add(now, static_cast<double>(counts.batches));
    requestRate_.add(now, static_cast<double>(counts.requests));
    busyRate_.add(now, counts.busySeconds);
    frame.displayThreads = async_->threads().display;
    frame.traceThreads = async_->threads().trace;
    frame.displayFps = displayRate_.rate();
    frame.samplesPerSecond = sampleRate_.rate();
    frame.batchesPerSecond = batchRate_.rate();
    frame.requestsPerSecond = requestRate_.rate();
    frame.traceBusyShare = busyRate_.rate();
    frame.mergedSamples = counts.merged - lastMerged_;
    lastMerged_ = counts.merged;
}

void RenderWorker::renderSessionFrame(const RenderRequest& request, const Camera& camera, DisplayFrame& frame) {
    std::unique_lock<std::mutex> cachesHeld;
    if (async_) cachesHeld = async_->holdCaches();
    session_->resize(request.width, request.height);
    if (refines(request)) return refineFrame(request, camera, frame);
    refinedView_.reset();
    frame.stats = session_->render(camera, film_);
}

bool RenderWorker::refines(const RenderRequest& request) const {
    // The difference view and the level overlay compare with or paint over
    // a plain frame, one ray through each pixel's centre.
    return refinement_ && session_->settings().pipeline == PipelineKind::Ray && !request.difference &&
           !request.cacheLevels;
}

void RenderWorker::refineFrame(const RenderRequest& request, const Camera& camera, DisplayFrame& frame) {
    const RefinedView view{camera, request.width, request.height, *config_, frameTime_, clearCount_};
    frame.refinementTarget = refinement_->target();
    if (refinedView_ != view) {
        // A view shown for the first time (every frame while the camera
        // moves) is the plain frame, as without --spp; its refinement starts
        // when the same view is asked for again.
        refinedView_ = view;
        refinement_->restart(request.width, request.height);
        frame.stats = session_->render(camera, film_);
        frame.refinedSamples = 0;
        return;
    }
    if (refinement_->complete()) {
        frame.refinedSamples = refinement_->target();  // film_ holds it already
        frame.refinementReused = true;
        return;
    }
    frame.stats = session_->renderSample(camera, layer_, refinement_->samples(), refinement_->nextSample());
    refinement_->add(layer_, film_, parallel_);
    frame.refinedSamples = refinement_->nextSample();
}

void RenderWorker::renderFrame(const RenderRequest& request, const Camera& camera, DisplayFrame& frame) {
    // The one place a frame is rendered, by the pipeline the settings ask
    // for; the Render Cache at its own rate when asked and the scene is still
    // (a scene that moves would move under its tracer).
    const bool autoPipeline = config_->pipeline == kAutoPipelineChoice;
    const bool stillScene = setup_.scene->animation.empty();
    const bool renderCache = session_->settings().pipeline == PipelineKind::RenderCache ||
                             (autoPipeline && request.showRenderCache && stillScene);
    const bool async = renderCache && request.renderCacheAsync && stillScene;
    frame.autoPipeline = autoPipeline;
    frame.shown = renderCache ? ShownPipeline::RenderCache : ShownPipeline::FullFrame;
    frame.renderCachePriming = false;
    frame.asyncRenderCache = async;
    showsAsync_ = async;
    if (async) {
        reconstructAsync(request, camera, frame);
        // Auto: until the samples of the whole image have come, the full
        // frame (the Render Cache would show the environment in their place).
        if (autoPipeline && frame.stats.renderCache && frame.stats.renderCache->refreshedAll) {
            frame.renderCachePriming = true;
            frame.shown = ShownPipeline::FullFrame;
            renderSessionFrame(request, camera, frame);
        }
    } else if (renderCache && autoPipeline) {
        if (!renderCacheSession_) {
            RenderSettings settings = settings_;
            settings.pipeline = PipelineKind::RenderCache;
            renderCacheSession_ = std::make_unique<RenderSession>(*setup_.scene, settings, *setup_.tracer, parallel_);
        }
        renderCacheSession_->resize(request.width, request.height);
        frame.stats = renderCacheSession_->render(camera, film_);
    } else {
        // Auto keeps the async Render Cache's samples for the camera's next move.
        if (!autoPipeline) async_.reset();
        renderSessionFrame(request, camera, frame);
    }
}

const RenderCacheOverlays* RenderWorker::shownOverlays(const DisplayFrame& frame) const {
    if (frame.shown != ShownPipeline::RenderCache) return nullptr;
    if (frame.asyncRenderCache) return async_->overlays();
    if (frame.autoPipeline) return renderCacheSession_->renderCacheOverlays();
    return session_->renderCacheOverlays();
}

void RenderWorker::renderOne(const RenderRequest& request, DisplayFrame& frame) {
    applyConfig(request.config, frame);
    if (request.clearCount != clearCount_) {
        clearCount_ = request.clearCount;
        async_.reset();  // its tracer may be using the caches; its samples go too
        session_->cache().clear();
        if (renderCacheSession_) renderCacheSession_->cache().clear();
    }
    if (request.pathRestartCount != pathRestartCount_) {
        pathRestartCount_ = request.pathRestartCount;
        pathFrame_ = 0;
    }
    const bool onPath = request.playPath;
    const Camera camera = onPath ? setup_.path.cameraAt(setup_.scene->camera, pathFrame_) : request.camera;

    const float time = setup_.scriptedFrames ? setup_.timeline.timeOf(pathFrame_) : request.time;
    session_->setTime(time);
    // Recorded only while the overlay is shown: otherwise the kernel does no
    // per-pixel work for it. The difference view hides it; the Render Cache
    // pipeline makes none (and turning it on would make that pipeline anew,
    // throwing its samples away).
    const bool showLevels = request.cacheLevels && !request.difference;
    session_->setRecordCacheLevels(showLevels && session_->settings().pipeline != PipelineKind::RenderCache);

    frameTime_ = setup_.scene->animation.empty() ? 0.0f : time;  // a still scene looks the same at any time
    frame.refinedSamples = 0;
    frame.refinementTarget = 0;
    frame.refinementReused = false;
    auto start = std::chrono::steady_clock::now();
    renderFrame(request, camera, frame);
    refinementComplete_ = frame.refinementReused || (frame.refinementTarget > 0 && frame.refinedSamples == frame.refinementTarget);
    frame.renderMs = millisecondsSince(start);

    start = std::chrono::steady_clock::now();
    encode(film_, frame.rgba, &display_);
    frame.inspectedObject = -1;
    frame.inspectorRgba.clear();
    // The async Render Cache's tracer merges stores into the caches between
    // its batches: kept out while the cubes are read here.
    std::unique_lock<std::mutex> cachesHeld;
    if (async_) cachesHeld = async_->holdCaches();
    const RayCache& cache = session_->cache();
    if (request.inspectObject >= 0 && cache.cachesObject(request.inspectObject)) {
        const CachingCube& cube = cache.cube(request.inspectObject);
        const auto dropped = cache.droppedByLastChange(request.inspectObject);
        const Image cross = cubeInspectorImage(cube, request.inspectorFaceSize, dropped);
        frame.inspectedDroppedTexels = 0;
        for (const std::uint64_t word : dropped) frame.inspectedDroppedTexels += std::popcount(word);
        encode(cross, frame.inspectorRgba);
        frame.inspectedObject = request.inspectObject;
        frame.inspectorWidth = cross.width();
        frame.inspectorHeight = cross.height();
        frame.inspectedInvalidPercent =
            100.0 * static_cast<double>(cube.texelCount() - cube.validCount()) / static_cast<double>(cube.texelCount());
    }
    frame.cacheBytes = cache.bytes();
    if (cachesHeld.owns_lock()) cachesHeld.unlock();
    // The difference view's heat map is made from the image without the overlays.
    const RenderCacheOverlays* overlays = shownOverlays(frame);
    if (overlays && !request.difference)
        paintRenderCacheOverlay(*overlays, static_cast<RenderCacheOverlay>(request.renderCacheOverlay), frame.rgba);
    frame.showsCacheLevels = false;
    if (showLevels && frame.shown == ShownPipeline::FullFrame)
        if (const CacheLevelImage* levels = session_->cacheLevels()) {
            paintCacheLevelOverlay(*levels, frame.rgba);
            frame.cacheLevelPixels = levels->counts();
            frame.showsCacheLevels = true;
        }
    frame.encodeMs = millisecondsSince(start);

    frame.showsDifference = false;
    frame.differenceMs = 0.0;
    if (request.difference) {
        start = std::chrono::steady_clock::now();
        uncached_->resize(request.width, request.height);
        uncached_->setTime(time);
        uncached_->render(camera, uncachedFilm_);
        encode(uncachedFilm_, uncachedRgba_);
        const double sum = differenceHeatMap(frame.rgba, uncachedRgba_, request.differenceGain, frame.rgba);
        frame.meanDifference = sum / (static_cast<double>(film_.width()) * static_cast<double>(film_.height()));
        frame.showsDifference = true;
        frame.differenceMs = millisecondsSince(start);
    }

    frame.serial = ++serial_;
    frame.width = film_.width();
    frame.height = film_.height();
    frame.camera = camera;
    frame.pathFrame = onPath ? pathFrame_ : -1;
    frame.reducedResolution = request.reducedResolution && !onPath;
    frame.configError = configError_;
    if (onPath) ++pathFrame_;
}

}  // namespace raycache
