#include "PathRender.h"

#include <gtest/gtest.h>

#include "core/Parallel.h"
#include "render/FrameRenderer.h"
#include "scene/BuiltinScenes.h"
#include "trace/TraceScene.h"

namespace raycache {

PathRender renderPath(const std::string& sceneName, CacheTechnique technique, int frames, bool still, int size,
                      int threads, int cacheResolution, const ProcessGroup* group, TileBalance balance, int cubeLevels,
                      std::int64_t prefillPerFrame, bool resolutionFromView, VisibleFill fill,
                      const CdctImprovements& improvements, CachePolicyMode policy,
                      const CachePolicyCosts& policyCosts) {
    const auto scene = makeBuiltinScene(sceneName);
    EXPECT_TRUE(scene.has_value()) << sceneName;
    if (!scene) return {};
    return renderPath(*scene, technique, frames, still, size, threads, cacheResolution, group, balance, cubeLevels,
                      prefillPerFrame, resolutionFromView, fill, improvements, policy, policyCosts);
}

PathRender renderPath(const Scene& sceneRef, CacheTechnique technique, int frames, bool still, int size, int threads,
                      int cacheResolution, const ProcessGroup* group, TileBalance balance, int cubeLevels,
                      std::int64_t prefillPerFrame, bool resolutionFromView, VisibleFill fill,
                      const CdctImprovements& improvements, CachePolicyMode policy,
                      const CachePolicyCosts& policyCosts) {
    const Scene* scene = &sceneRef;
    RenderSettings settings;
    settings.width = settings.height = size;
    settings.threads = threads;
    settings.cache.techniqueOverride = technique;
    settings.cache.resolutionOverride = cacheResolution;
    settings.tileBalance = balance;
    settings.cache.cubeLevels = cubeLevels;
    settings.cache.prefillTexelsPerFrame = prefillPerFrame;
    settings.cache.resolutionFromView = resolutionFromView;
    settings.cache.visibleFill = fill;
    settings.cache.cdctImprovements = improvements;
    settings.cache.policy = policy;
    settings.cache.policyCosts = policyCosts;
    const TraceScene tracer(*scene);
    const Parallel parallel(threads);
    RayCache cache(*scene, settings.cache);
    const FrameRenderer renderer(*scene, tracer, settings, parallel, &cache, group);
    PathRender run;
    for (int f = 0; f < frames; ++f) {
        Image film;
        const Camera camera = still ? scene->camera : scene->cameraPath.cameraAt(scene->camera, f);
        run.stats.push_back(renderer.render(camera, film));
        run.frames.push_back(std::move(film));
    }
    for (std::size_t i = 0; i < scene->objects.size(); ++i) {
        if (!cache.cachesObject(static_cast<int>(i))) continue;
        const CachingCube& cube = cache.cube(static_cast<int>(i));
        run.texels.emplace_back(cube.texels().begin(), cube.texels().end());
        if (cube.hasDepth()) run.texels.emplace_back(cube.depthWords().begin(), cube.depthWords().end());
        const CoarseLevels& coarse = cache.coarseLevels(static_cast<int>(i));
        for (int k = 1; k < coarse.levelCount(); ++k)
            run.texels.emplace_back(coarse.level(k).texels().begin(), coarse.level(k).texels().end());
    }
    return run;
}

}  // namespace raycache
