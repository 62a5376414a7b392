#pragma once
// The deferred passes of the hybrid pipeline (its steps 2-4 in Ruff et al. 2013), shared by
// both G-buffer producers: the tile kernel (render/TileKernel.h) starting from
// the G-buffer's surfaces, so shadow rays go only to pixels that hold a
// surface and reflection/refraction rays only to pixels whose material needs
// them, answered by the same caches as in the ray pipeline; then composition.
#include "core/Image.h"
#include "core/Parallel.h"
#include "raster/GBuffer.h"
#include "render/CacheLevelImage.h"
#include "render/FrameStats.h"
#include "render/RenderSettings.h"
#include "render/TileKernel.h"
#include "scene/Camera.h"

namespace raycache {

class DeferredShading {
public:
    // With `cache` (may be null), caching objects' secondary rays go through
    // it, and its frame hooks run around every frame's secondary pass.
    DeferredShading(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                    const Parallel& parallel, RayCache* cache);

    // Shades the frame `camera` sees from `gbuffer` (the settings' size) into
    // `film`; adds its rays to stats.rays, sets stats.cache and the shadows,
    // secondary and compose times of stats.phases (the kernel's first bounce,
    // its later bounces and the film writes; they run per tile in one
    // parallel pass, whose wall time is split in proportion to the time the
    // workers spent in each; the cache's frame end counts as secondary).
    // Images and caches do not depend on the thread count.
    // With settings.recordCacheLevels and `levels`, `levels` (resized to the
    // film's size) gets the frame's cache-level record; otherwise it is not touched.
    void shade(const Camera& camera, const GBufferView& gbuffer, Image& film, FrameStats& stats,
               CacheLevelImage* levels = nullptr);

private:
    RenderSettings settings_;
    const Parallel& parallel_;
    RayCache* cache_;
    TileKernel kernel_;
    std::vector<TileScratch> scratch_;  // per-worker buffers kept from frame to frame
};

}  // namespace raycache
