#include "app/ViewCommand.h"

#include <algorithm>
#include <cmath>

#include "core/Errors.h"
#include "render/ImageWriter.h"
#include "cache/RayCache.h"
#include "viewer/PipelineChoice.h"
#include "viewer/TechniqueChoice.h"
#include "viewer/Viewer.h"

namespace raycache {

void runViewCommand(const ViewCommandOptions& options, std::ostream& out, std::ostream& notes) {
    validateRenderJobOptions(options.job);
    if (!options.screenshotPath.empty()) checkWritableImagePath(options.screenshotPath);
    if (options.warmupFrames < 0) throw InputError("--warmup must be >= 0");
    if (!(std::isfinite(options.movingScale) && options.movingScale >= 0.1f && options.movingScale <= 1.0f))
        throw InputError("--moving-scale must be between 0.1 and 1");
    if (options.renderCacheTraceThreads < 0) throw InputError("--render-cache-trace-threads must be >= 0");
    if (options.renderCacheDisplayThreads < 0) throw InputError("--render-cache-display-threads must be >= 0");
    if (!(std::isfinite(options.renderCacheRequestFrames) && options.renderCacheRequestFrames >= 0.0 &&
          options.renderCacheRequestFrames <= 100.0))
        throw InputError("--render-cache-request-frames must be between 0 and 100");
    if (!(std::isfinite(options.renderCacheReshadeMs) && options.renderCacheReshadeMs >= 0.0 &&
          options.renderCacheReshadeMs <= 1000.0))
        throw InputError("--render-cache-reshade-ms must be between 0 and 1000");
    if (!(std::isfinite(options.targetFps) && options.targetFps >= 1.0 && options.targetFps <= 1000.0))
        throw InputError("--target-fps must be between 1 and 1000");
    if (options.job.cacheIdeal) throw InputError("--cache-ideal is a benchmark switch; the viewer does not take it");
    if (options.job.samplesPerPixel != 1 && options.pipeline != ViewerPipeline::Ray &&
        options.pipeline != ViewerPipeline::Auto)
        throw InputError("--spp: the viewer refines full frames of the ray pipeline (--pipeline ray or auto); the " +
                         std::string(viewerPipelineName(options.pipeline)) + " pipeline shows one ray per pixel");

    // The viewer renders one ray per pixel and refines a still view itself
    // (viewer/ProgressiveFilm.h), one sample layer a frame.
    RenderJobOptions oneRayPerPixel = options.job;
    oneRayPerPixel.samplesPerPixel = 1;
    RenderJob job = prepareRenderJob(oneRayPerPixel);
    printSceneNotes(job.scene, notes);
    // An interactive frame must not stall for seconds while improved CDCT
    // fills whole cubes (1.5 M rays per 512² cube): spread it, about half
    // an uncached frame's rays a frame (docs/viewer.md).
    if (!options.job.cdctPrefillPerFrame)
        job.settings.cache.prefillTexelsPerFrame =
            std::max<std::int64_t>(1, static_cast<std::int64_t>(job.settings.width) * job.settings.height / 2);
    ViewerRenderConfig config;
    // The command line's choices become the panel's starting values.
    config.technique = techniqueChoiceIndex(options.job.technique);
    config.cacheResolution = options.job.cacheResolution;
    config.cdctStep = options.job.cdctStep;
    config.cdctEpsilon = options.job.cdctEpsilon;
    config.maxDepth = options.job.maxDepth;
    // The viewer's hybrid pipeline always takes its G-buffer from packets (viewer/PipelineChoice.h).
    config.pipeline = static_cast<int>(options.pipeline);

    config.accelerator = job.settings.trace.accelerator;

    ViewerOptions viewer;
    // Without --frames the viewer is interactive; the frame count then only
    // matters to RenderJob's validation.
    if (options.job.frames) viewer.scriptedFrames = job.frames;
    viewer.warmupFrames = options.warmupFrames;
    viewer.screenshotPath = options.screenshotPath;
    viewer.hideUi = options.hideUi;
    viewer.vsync = !options.noVsync;
    viewer.movingScale = options.movingScale;
    viewer.difference = options.difference;
    viewer.cacheLevels = options.levelOverlay;
    // Scripted runs repeat `raycache render`'s frames unless asked otherwise.
    viewer.renderCacheDisplay =
        options.renderCacheDisplay.value_or(viewer.scriptedFrames ? RenderCacheDisplay::Sync : RenderCacheDisplay::Async);
    viewer.targetFrameMs = 1000.0 / options.targetFps;
    viewer.renderCacheTraceThreads = options.renderCacheTraceThreads;
    viewer.renderCacheDisplayThreads = options.renderCacheDisplayThreads;
    viewer.renderCacheRequestFrames = options.renderCacheRequestFrames;
    viewer.renderCacheReshadeMs = options.renderCacheReshadeMs;
    viewer.samplesPerPixel = options.job.samplesPerPixel;
    if (!options.inspectObject.empty()) {
        const auto& objects = job.scene.objects;
        const auto found = std::find_if(objects.begin(), objects.end(),
                                        [&](const SceneObject& o) { return o.name == options.inspectObject; });
        if (found == objects.end())
            throw InputError("--inspect: scene " + job.scene.name + " has no object '" + options.inspectObject + "'");
        const RenderSettings settings = applyViewerRenderConfig(job.settings, config);
        if (RayCache::techniqueFor(*found, settings.cache) == CacheTechnique::None)
            throw InputError("--inspect: object '" + options.inspectObject + "' has no caching cube under this technique");
        viewer.inspectObject = static_cast<int>(found - objects.begin());
    }
    Viewer(std::move(job), config, viewer).run(out);
}

}  // namespace raycache
