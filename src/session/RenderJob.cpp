#include "session/RenderJob.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/Errors.h"
#include "core/SystemMemory.h"
#include "scene/SceneLoader.h"

namespace raycache {

namespace {

constexpr int kMaxImageSide = 16384;
constexpr int kMaxJobFrames = 1000000;
constexpr int kMaxSamplesPerPixel = 4096;

CameraPath chooseCameraPath(const Scene& scene, const std::optional<CameraPathKind>& override) {
    if (!override) return scene.cameraPath;
    CameraPath path;
    if (*override == CameraPathKind::Static) return path;
    path.kind = *override;
    // Keep the scene's own centre and speed when it already orbits or pans.
    const bool sceneTurns =
        scene.cameraPath.kind == CameraPathKind::Orbit || scene.cameraPath.kind == CameraPathKind::Pan;
    path.center = scene.cameraPath.kind == CameraPathKind::Orbit ? scene.cameraPath.center : scene.camera.lookAt;
    path.degreesPerFrame = sceneTurns ? scene.cameraPath.degreesPerFrame : 1.0f;
    return path;
}

}  // namespace

void applyRenderCacheOverrides(const RenderCacheOverrides& o, RenderCacheSettings& rc) {
    if (o.budget) rc.budget = *o.budget;
    if (o.targetFrameMs) rc.targetFrameMs = *o.targetFrameMs;
    if (o.alpha) rc.alpha = *o.alpha;
    if (o.predictShare) rc.predictShare = *o.predictShare;
    if (o.maxAge) rc.maxAge = *o.maxAge;
    if (o.seed) rc.seed = *o.seed;
    if (o.margin) rc.margin = *o.margin;
    if (o.depthCullThreshold) rc.depthCullThreshold = *o.depthCullThreshold;
    if (o.requestTileSize) rc.requestTileSize = *o.requestTileSize;
    if (o.reflections) rc.reflections = *o.reflections;
    if (o.textureRefetch) rc.textureRefetch = *o.textureRefetch;
    if (o.reshadeInterval) rc.reshadeInterval = *o.reshadeInterval;
}

void validateRenderJobOptions(const RenderJobOptions& o) {
    if (o.width < 1 || o.height < 1 || o.width > kMaxImageSide || o.height > kMaxImageSide)
        throw InputError("--width/--height must be between 1 and " + std::to_string(kMaxImageSide));
    if (o.frames && (*o.frames < 1 || *o.frames > kMaxJobFrames))
        throw InputError("--frames must be between 1 and " + std::to_string(kMaxJobFrames));
    if (!(std::isfinite(o.time) && std::fabs(o.time) <= kMaxAnimationSeconds))
        throw InputError("--time must be a finite number of seconds within ±" +
                         std::to_string(static_cast<int>(kMaxAnimationSeconds)));
    if (o.fps && !(std::isfinite(*o.fps) && *o.fps > 0.0f && *o.fps <= 1000.0f))
        throw InputError("--fps must be a number in (0, 1000]");
    if (o.maxDepth < 1 || o.maxDepth > 64) throw InputError("--max-depth must be between 1 and 64");
    if (!(o.minWeight >= 0.0f && o.minWeight <= 1.0f)) throw InputError("--min-weight must be in [0, 1]");
    if (o.threads < 0 || o.threads > 1024) throw InputError("--threads must be between 0 (all) and 1024");
    if (o.samplesPerPixel < 1 || o.samplesPerPixel > kMaxSamplesPerPixel)
        throw InputError("--spp must be between 1 and " + std::to_string(kMaxSamplesPerPixel) + " (got " +
                         std::to_string(o.samplesPerPixel) + ")");
    if (o.exposure && !(std::isfinite(*o.exposure) && std::fabs(*o.exposure) <= kMaxExposureStops))
        throw InputError("--exposure must be a finite number of stops within ±" +
                         std::to_string(static_cast<int>(kMaxExposureStops)));
    const auto positive = [](const std::optional<float>& v, const char* flag) {
        if (v && !(std::isfinite(*v) && *v > 0.0f))
            throw InputError(std::string(flag) + " must be a finite number > 0");
    };
    positive(o.cdctStep, "--cdct-step");
    positive(o.cdctEpsilon, "--cdct-epsilon");
    positive(o.cdctMaxDepth, "--cdct-max-depth");
    positive(o.cdctTolerance, "--cdct-tolerance");
    if (o.cdctPrefillPerFrame && (*o.cdctPrefillPerFrame < 0 || *o.cdctPrefillPerFrame > (std::int64_t{1} << 40)))
        throw InputError("--cdct-prefill-per-frame must be between 0 (whole cubes at once) and 2^40 (got " +
                         std::to_string(*o.cdctPrefillPerFrame) + ")");
    if (o.cdctStep && o.cdctEpsilon && !(*o.cdctEpsilon < *o.cdctStep))
        throw InputError("--cdct-epsilon must be smaller than --cdct-step");
    if (o.cacheResolution && (*o.cacheResolution < CacheSettings::kMinFaceResolution ||
                              *o.cacheResolution > CacheSettings::kMaxFaceResolution))
        throw InputError("--cache-res must be between " + std::to_string(CacheSettings::kMinFaceResolution) +
                         " and " + std::to_string(CacheSettings::kMaxFaceResolution) + " (got " +
                         std::to_string(*o.cacheResolution) + ")");
    if (o.cacheLevels < 1 || o.cacheLevels > kMaxCubeLevels)
        throw InputError("--cache-levels must be between 1 and " + std::to_string(kMaxCubeLevels) + " (got " +
                         std::to_string(o.cacheLevels) + ")");
    if (!(std::isfinite(o.cacheLevelError) && o.cacheLevelError > 0.0f && o.cacheLevelError <= 1000.0f))
        throw InputError("--cache-level-error must be a finite number in (0, 1000]");
    if (o.cacheBudgetMiB && !(std::isfinite(*o.cacheBudgetMiB) && *o.cacheBudgetMiB > 0.0 && *o.cacheBudgetMiB <= 1e9))
        throw InputError("--cache-budget must be a finite number of MiB in (0, 1e9]");
    // The --rc-* values alone, over the defaults: each error names its option.
    RenderCacheSettings rc;
    applyRenderCacheOverrides(o.renderCache, rc);
    validateRenderCacheSettings(rc);
    if (o.path && std::ranges::find(kPathOptionKinds, *o.path) == kPathOptionKinds.end())
        throw InputError(std::string("--path ") + cameraPathKindName(*o.path) +
                         ": a keyframed path comes from a scene file");
}

RenderJob prepareRenderJob(const RenderJobOptions& options) {
    validateRenderJobOptions(options);
    RenderJob job;
    job.scene = loadScene(options.scene, options.blinnPhongGltfMaterials);
    job.path = chooseCameraPath(job.scene, options.path);
    job.frames = options.frames.value_or(job.scene.defaultFrames);
    job.timeline = FrameTimeline{options.time, options.fps.value_or(job.scene.fps)};

    RenderSettings& settings = job.settings;
    settings.width = options.width;
    settings.height = options.height;
    settings.maxDepth = options.maxDepth;
    settings.minWeight = options.minWeight;
    settings.threads = options.threads;
    settings.samplesPerPixel = options.samplesPerPixel;
    settings.cache.techniqueOverride = options.technique;
    settings.cache.cdctStepOverride = options.cdctStep;
    settings.cache.cdctEpsilonOverride = options.cdctEpsilon;
    settings.cache.cdctMaxDepthOverride = options.cdctMaxDepth;
    settings.cache.cdctToleranceOverride = options.cdctTolerance;
    settings.cache.prefillTexelsPerFrame = options.cdctPrefillPerFrame.value_or(0);
    settings.cache.resolutionOverride = options.cacheResolution;
    settings.cache.cubeLevels = options.cacheLevels;
    settings.cache.levelErrorBound = options.cacheLevelError;
    settings.cache.resolutionFromView = options.cacheResFromView;
    settings.cache.visibleFill = options.cacheFill;
    settings.cache.ideal = options.cacheIdeal;
    settings.cache.skipStoresReachingChanges = !options.cacheStoreChanging;
    settings.cache.policy = options.cachePolicy;
    settings.stageTimes = options.stageTimes;
    settings.tileBalance = options.tileBalance;
    // Command-line options win over the scene file's, which win over the defaults.
    const SceneRenderDefaults& fromScene = job.scene.render;
    settings.pipeline = options.pipeline.value_or(fromScene.pipeline.value_or(PipelineKind::Ray));
    settings.trace.accelerator = options.accel.value_or(fromScene.accel.value_or(Accelerator::Embree));
    if (settings.samplesPerPixel != 1 && settings.pipeline != PipelineKind::Ray)
        throw InputError("--spp " + std::to_string(settings.samplesPerPixel) + " needs --pipeline ray (the " +
                         pipelineKindName(settings.pipeline) + " pipeline renders one ray per pixel)");
    applyRenderCacheOverrides(fromScene.renderCache, settings.renderCache);
    applyRenderCacheOverrides(options.renderCache, settings.renderCache);
    settings.gbuffer = options.gbuffer;
    job.display.exposure = options.exposure.value_or(fromScene.exposure.value_or(0.0f));
    job.display.view = options.viewTransform.value_or(fromScene.viewTransform.value_or(ViewTransform::Standard));
    // The cubes' budget: the option, else the scene file's, else half the machine's memory.
    const double budgetMiB = options.cacheBudgetMiB.value_or(
        fromScene.cacheBudgetMiB.value_or(static_cast<double>(physicalMemoryBytes()) / 2.0 / (1024.0 * 1024.0)));
    if (budgetMiB > 0.0) settings.cache.memoryBudget = static_cast<std::size_t>(budgetMiB * 1024.0 * 1024.0);
    job.cacheBudgetNote = RayCache::validate(job.scene, settings.cache).note;
    return job;
}

void printSceneNotes(const Scene& scene, std::ostream& out) {
    for (const std::string& note : scene.notes) out << "note: " << note << "\n";
}

}  // namespace raycache
