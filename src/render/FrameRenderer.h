#pragma once
// Renders one frame: primary rays per 16x16 tile as coherent packets, then
// Whitted shading per pixel, tiles spread over the worker threads.
#include "core/Image.h"
#include "core/Parallel.h"
#include "render/FrameStats.h"
#include "render/RenderSettings.h"
#include "render/WhittedIntegrator.h"
#include "scene/Camera.h"

namespace raycache {

class FrameRenderer {
public:
    // With `cache` (may be null), caching objects' secondary rays go through
    // it, and its frame hooks run around every frame.
    FrameRenderer(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                  const Parallel& parallel, RayCache* cache = nullptr);

    // Fills `film` (resized to the settings' size) with linear radiance and
    // returns what the frame did. Images and caches do not depend on the
    // thread count.
    FrameStats render(const Camera& camera, Image& film) const;

private:
    const Scene& scene_;
    const TraceScene& tracer_;
    RenderSettings settings_;
    const Parallel& parallel_;
    RayCache* cache_;
    WhittedIntegrator integrator_;
};

}  // namespace raycache
