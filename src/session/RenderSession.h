#pragma once
// A scene made ready to render frames: its tracer, its caches, its worker
// threads and the pipeline the settings ask for, owned together. The CLI,
// the experiments, the benchmarks and the viewer all render through one of
// these; nobody assembles the parts by hand.
#include <memory>
#include <optional>
#include <string>

#include "cache/RayCache.h"
#include "core/Image.h"
#include "core/Parallel.h"
#include "core/ProcessGroup.h"
#include "render/FramePipeline.h"
#include "render/FrameStats.h"
#include "render/RenderSettings.h"
#include "scene/Camera.h"
#include "scene/Scene.h"
#include "trace/TraceScene.h"

namespace raycache {

class RenderSession {
public:
    // Builds its own tracer and worker threads. Throws InputError for invalid
    // cache settings before building anything, RuntimeError when the hybrid
    // pipeline is forced onto OpenGL and no context can be made. `scene` must
    // outlive the session.
    // With `group` (may be null; must outlive the session) of more than one
    // process, each frame's tiles are shared among them (render/FrameRenderer.h):
    // every process must make the same calls in the same order.
    RenderSession(const Scene& scene, const RenderSettings& settings, const ProcessGroup* group = nullptr);
    // Shares a tracer and threads (which must outlive it) with other sessions
    // on the same scene, e.g. the variants an experiment compares.
    RenderSession(const Scene& scene, const RenderSettings& settings, const TraceScene& tracer,
                  const Parallel& parallel);
    ~RenderSession();
    RenderSession(const RenderSession&) = delete;
    RenderSession& operator=(const RenderSession&) = delete;

    // Renders what `camera` sees into `film` (resized to the session's size).
    // Images and caches do not depend on the thread count. The stats include
    // the scene update of setTime calls since the last frame.
    FrameStats render(const Camera& camera, Image& film);
    // Renders one jittered sample layer of what `camera` sees into `layer`
    // (FramePipeline::renderSample): the ray pipeline only (RuntimeError
    // otherwise).
    FrameStats renderSample(const Camera& camera, Image& layer, const PixelSamples& samples, int sample);
    // Puts an animated scene in its pose at `seconds`: moves the tracer's
    // objects, invalidates what the caches saw of what changed, tells the
    // pipeline. Does nothing for a still scene. A session that shares its
    // tracer cannot animate (the others would see the change): RuntimeError.
    SceneUpdateStats setTime(float seconds);
    // The scene as the last setTime left it (the scene itself when still).
    const Scene& scene() const { return scene_; }
    // Changes the image size of later frames; the caches stay as they are.
    void resize(int width, int height);
    // Turns the cache-level record of later frames on or off
    // (RenderSettings::recordCacheLevels); the caches stay as they are. Like
    // resize(), a change makes the pipeline anew (the Render Cache's samples
    // start again). InputError with several processes.
    void setRecordCacheLevels(bool on);

    RayCache& cache() { return cache_; }
    const RayCache& cache() const { return cache_; }
    const RenderSettings& settings() const { return settings_; }
    const TraceScene& tracer() const { return *tracer_; }
    const Parallel& parallel() const { return *parallel_; }
    // Which pipeline renders, and for the hybrid one where its G-buffer comes from.
    std::string description() const { return pipeline_->description(); }
    // The Render Cache pipeline's maps of the last frame; null for the others.
    const RenderCacheOverlays* renderCacheOverlays() const { return pipeline_->renderCacheOverlays(); }
    // The last frame's cache-level record (render/CacheLevelImage.h): null
    // unless recorded, and for the Render Cache pipeline.
    const CacheLevelImage* cacheLevels() const { return pipeline_->cacheLevels(); }

private:
    // A frame made by `make` (the pipeline's render or renderSample): the
    // tracer prepared for the camera first, the grids' build and the scene
    // update since the last frame added to its stats.
    template <typename Make>
    FrameStats frame(const Camera& camera, Make&& make);

    const Scene& source_;
    std::unique_ptr<Scene> posed_;  // the current pose of an animated scene; null when still
    const Scene& scene_;            // *posed_, or source_ when still
    std::optional<SceneUpdateStats> pendingUpdate_;
    RenderSettings settings_;
    RayCache cache_;  // first: its constructor rejects bad settings before any heavy work
    std::unique_ptr<TraceScene> ownTracer_;
    std::unique_ptr<Parallel> ownParallel_;
    const TraceScene* tracer_;
    const Parallel* parallel_;
    const ProcessGroup* group_ = nullptr;
    std::unique_ptr<FramePipeline> pipeline_;
};

}  // namespace raycache
