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
#include "viewer/RenderCacheOverlayImage.h"

namespace raycache {

RenderWorker::RenderWorker(RenderWorkerSetup setup, FrameHandoff& handoff)
    : setup_(std::move(setup)), handoff_(handoff), parallel_(setup_.base.threads), settings_(setup_.base),
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
                // Render again when the request changed, or when asked to keep going.
                wake_.wait(lock, [&] {
                    return stop_ || (request_ && (requestSerial_ != renderedSerial || request_->continuous ||
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

void RenderWorker::encode(const Image& film, std::vector<std::uint8_t>& rgba) const {
    rgba.resize(static_cast<std::size_t>(film.width()) * static_cast<std::size_t>(film.height()) * 4);
    constexpr int kRowsPerTask = 8;
    const int tasks = (film.height() + kRowsPerTask - 1) / kRowsPerTask;
    parallel_.forEachIndex(tasks, [&](int task, int) {
        const int y0 = task * kRowsPerTask;
        encoder_.encodeRows(film, y0, std::min(y0 + kRowsPerTask, film.height()), rgba);
    });
}

void RenderWorker::renderOne(const RenderRequest& request, DisplayFrame& frame) {
    applyConfig(request.config, frame);
    if (request.clearCount != clearCount_) {
        clearCount_ = request.clearCount;
        session_->cache().clear();
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

    // The one place a frame is rendered, by the pipeline the settings ask for.
    session_->resize(request.width, request.height);
    auto start = std::chrono::steady_clock::now();
    frame.stats = session_->render(camera, film_);
    frame.renderMs = millisecondsSince(start);

    start = std::chrono::steady_clock::now();
    encode(film_, frame.rgba);
    frame.inspectedObject = -1;
    frame.inspectorRgba.clear();
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
    // The difference view's heat map is made from the image without the overlays.
    if (const RenderCacheOverlays* overlays = session_->renderCacheOverlays(); overlays && !request.difference)
        paintRenderCacheOverlay(*overlays, static_cast<RenderCacheOverlay>(request.renderCacheOverlay), frame.rgba);
    frame.showsCacheLevels = false;
    if (showLevels)
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
    frame.cacheBytes = cache.bytes();
    frame.configError = configError_;
    if (onPath) ++pathFrame_;
}

}  // namespace raycache
