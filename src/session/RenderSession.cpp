#include "session/RenderSession.h"

#include <chrono>

#include "core/Elapsed.h"
#include "core/Errors.h"

#include "scene/ScenePose.h"
#include "session/PipelineFactory.h"

namespace raycache {

namespace {

std::unique_ptr<Scene> copyIfAnimated(const Scene& scene) {
    return scene.animation.empty() ? nullptr : std::make_unique<Scene>(scene);
}

using Clock = std::chrono::steady_clock;

}  // namespace

RenderSession::RenderSession(const Scene& scene, const RenderSettings& settings, const ProcessGroup* group)
    : source_(scene), posed_(copyIfAnimated(scene)), scene_(posed_ ? *posed_ : scene), settings_(settings),
      cache_(scene_, settings.cache), ownTracer_(std::make_unique<TraceScene>(scene_, settings.trace)),
      ownParallel_(std::make_unique<Parallel>(settings.threads)), tracer_(ownTracer_.get()),
      parallel_(ownParallel_.get()), group_(group),
      pipeline_(makeFramePipeline(scene_, *tracer_, settings_, *parallel_, &cache_, group_)) {}

RenderSession::RenderSession(const Scene& scene, const RenderSettings& settings, const TraceScene& tracer,
                             const Parallel& parallel)
    : source_(scene), posed_(copyIfAnimated(scene)), scene_(posed_ ? *posed_ : scene), settings_(settings),
      cache_(scene_, settings.cache), tracer_(&tracer), parallel_(&parallel),
      pipeline_(makeFramePipeline(scene_, tracer, settings_, parallel, &cache_)) {}

RenderSession::~RenderSession() = default;

template <typename Make>
FrameStats RenderSession::frame(const Camera& camera, Make&& make) {
    // The grids are rebuilt every frame from the posed scene; their build is part of the frame.
    const auto buildStart = Clock::now();
    tracer_->prepareFrame(scene_, camera, settings_.width, settings_.height, *parallel_);
    const double gridBuildMs = millisecondsSince(buildStart);
    FrameStats stats = make();
    if (tracer_->accelerator() == Accelerator::Grids) {
        stats.trace = tracer_->frameStats();
        stats.gridBuildMs = gridBuildMs;
    }
    stats.sceneUpdate = pendingUpdate_;
    pendingUpdate_.reset();
    return stats;
}

FrameStats RenderSession::render(const Camera& camera, Image& film) {
    return frame(camera, [&] { return pipeline_->render(camera, film); });
}

FrameStats RenderSession::renderSample(const Camera& camera, Image& layer, const PixelSamples& samples, int sample) {
    return frame(camera, [&] { return pipeline_->renderSample(camera, layer, samples, sample); });
}

SceneUpdateStats RenderSession::setTime(float seconds) {
    SceneUpdateStats update;
    if (!posed_) return update;
    const auto start = Clock::now();
    const SceneChanges changes = poseScene(source_, seconds, *posed_);
    update.poseMs = millisecondsSince(start);
    update.objectsChanged = static_cast<int>(changes.objects.size());
    update.lightsChanged = static_cast<int>(changes.lights.size());
    if (!changes.empty()) {
        if (!ownTracer_) throw RuntimeError("a render session that shares its tracer cannot animate its scene");
        auto phase = Clock::now();
        ownTracer_->update(*posed_, changes.objects);
        update.tracerMs = millisecondsSince(phase);
        phase = Clock::now();
        update.texelsInvalidated =
            cache_.sceneChanged(*posed_, changes, [&](int count, const std::function<void(int)>& body) {
                parallel_->forEachIndex(count, [&](int part, int) { body(part); });
            });
        update.cacheMs = millisecondsSince(phase);
        pipeline_->sceneChanged(changes);
    }
    update.milliseconds = millisecondsSince(start);
    // Several updates before one frame: the frame reports their sum.
    if (pendingUpdate_) *pendingUpdate_ += update;
    else pendingUpdate_ = update;
    return update;
}

void RenderSession::setRecordCacheLevels(bool on) {
    if (on == settings_.recordCacheLevels) return;
    settings_.recordCacheLevels = on;
    try {
        pipeline_ = makeFramePipeline(scene_, *tracer_, settings_, *parallel_, &cache_, group_);
    } catch (...) {
        settings_.recordCacheLevels = !on;  // the old pipeline stays, and the settings it was made with
        throw;
    }
}

void RenderSession::resize(int width, int height) {
    if (width == settings_.width && height == settings_.height) return;
    settings_.width = width;
    settings_.height = height;
    pipeline_ = makeFramePipeline(scene_, *tracer_, settings_, *parallel_, &cache_, group_);
}

}  // namespace raycache
