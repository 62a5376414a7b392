#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include "cache/CacheStats.h"
#include "core/RayCounts.h"
#include "render/RenderCacheStats.h"
#include "trace/TraceScene.h"

namespace raycache {

// Wall time of the hybrid pipeline's phases in one frame, in milliseconds
// (Ruff et al. 2013). `raster` is the G-buffer pass: OpenGL drawing, or the
// primary-ray packets of the fallback (whose `readback` is then 0).
struct PhaseTimes {
    double raster = 0.0;
    double readback = 0.0;
    double shadows = 0.0;    // shadow rays of surface pixels and direct light
    double secondary = 0.0;  // reflection/refraction of the pixels that need them
    double compose = 0.0;    // direct + secondary, background where there is no surface
};

// CPU time the tile kernel's stages took in one frame, summed over the
// workers, in milliseconds (RenderSettings::stageTimes; render/TileKernel.h).
struct StageTimes {
    double firstHits = 0.0;       // camera rays as packets, a G-buffer read, or pre-fill rays
    double surfaces = 0.0;        // the surface at every hit
    double shadowRays = 0.0;      // shadow queries and their rays
    double directShading = 0.0;   // Blinn-Phong of every hit
    double secondaryRays = 0.0;   // reflected and refracted rays spawned
    double reuseLookups = 0.0;    // cache lookups of rays leaving caching objects
    double traceSecondary = 0.0;  // the rays no cache answered, traced together
    double resolve = 0.0;         // colours gathered up the ray trees, cache stores queued
    double compose = 0.0;         // colours written to the film
    double visibleFill = 0.0;     // cubes filled from the surfaces the camera saw (visibility rays, stores)
    double cacheFrameEnd = 0.0;   // wall time: pre-fill and the merge of queued stores
    // Surface points the kernel shaded (every wave's hits): the unit of the
    // stages' ns-per-hit figures.
    std::uint64_t hitsShaded = 0;

    // A stage's CPU time per shaded hit, ns (0 when nothing was shaded).
    double nsPerHit(double milliseconds) const {
        return hitsShaded == 0 ? 0.0 : milliseconds * 1e6 / static_cast<double>(hitsShaded);
    }

    double total() const {
        return firstHits + surfaces + shadowRays + directShading + secondaryRays + reuseLookups + traceSecondary +
               resolve + compose + visibleFill + cacheFrameEnd;
    }
    StageTimes& operator+=(const StageTimes& o) {
        firstHits += o.firstHits;
        surfaces += o.surfaces;
        shadowRays += o.shadowRays;
        directShading += o.directShading;
        secondaryRays += o.secondaryRays;
        reuseLookups += o.reuseLookups;
        traceSecondary += o.traceSecondary;
        resolve += o.resolve;
        compose += o.compose;
        visibleFill += o.visibleFill;
        cacheFrameEnd += o.cacheFrameEnd;
        hitsShaded += o.hitsShaded;
        return *this;
    }
};

// What moving the scene to the frame's time cost and touched
// (RenderSession::setTime): posing, the tracer's update and the caches'
// invalidation, in wall milliseconds.
struct SceneUpdateStats {
    double milliseconds = 0.0;
    double poseMs = 0.0;     // objects, meshes and lights put in their pose
    double tracerMs = 0.0;   // instance transforms, refits, the top-level rebuild
    double cacheMs = 0.0;    // cubes moved, texels invalidated
    int objectsChanged = 0;
    int lightsChanged = 0;
    std::int64_t texelsInvalidated = 0;

    SceneUpdateStats& operator+=(const SceneUpdateStats& o) {
        milliseconds += o.milliseconds;
        poseMs += o.poseMs;
        tracerMs += o.tracerMs;
        cacheMs += o.cacheMs;
        objectsChanged += o.objectsChanged;
        lightsChanged += o.lightsChanged;
        texelsInvalidated += o.texelsInvalidated;
        return *this;
    }
};

// A frame shared among several processes (core/ProcessGroup.h), as process
// 0 sees it after gathering the others' results.
struct ClusterStats {
    int processes = 1;
    const char* assignment = "static tiles";  // "static tiles", "dynamic tiles" or "whole frames"
    std::vector<int> tilesPerProcess;
    // Sum of the tile kernel's CPU time per process over their mean: 1 is a
    // perfect balance, 2 means the busiest process worked twice the mean.
    double imbalance = 1.0;
    std::uint64_t storeBytes = 0;    // cache stores and counters exchanged: every process's, summed
    std::uint64_t prefillBytes = 0;  // improved CDCT: pre-filled texel rows exchanged, every process's, summed
    std::uint64_t imageBytes = 0;    // pixels of other processes' tiles gathered to process 0
    std::uint64_t controlBytes = 0;  // tile assignment, tile costs and statistics
};

// What one rendered frame did.
struct FrameStats {
    RayCounts rays;
    std::optional<FrameCacheStats> cache;  // present when caches were in use
    std::optional<PhaseTimes> phases;      // present for the hybrid pipeline
    std::optional<StageTimes> stages;      // present when RenderSettings::stageTimes is set
    std::optional<RenderCacheStats> renderCache;  // present for the Render Cache pipeline
    std::optional<SceneUpdateStats> sceneUpdate;  // present for animated scenes
    std::optional<ClusterStats> cluster;          // present when several processes rendered the frame
    // The grids' per-frame build and the rays they answered (present with
    // the grids accelerator; docs/grids.md).
    std::optional<FrameTraceStats> trace;
    double gridBuildMs = 0.0;  // wall time of TraceScene::prepareFrame
};

}  // namespace raycache
