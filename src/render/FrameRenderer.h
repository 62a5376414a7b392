#pragma once
// Renders one frame: primary rays per 16x16 tile as coherent packets, then
// Whitted shading per pixel, tiles spread over the worker threads.
#include "core/Image.h"
#include "core/Parallel.h"
#include "core/RayCounts.h"
#include "render/RenderSettings.h"
#include "render/WhittedIntegrator.h"
#include "scene/Camera.h"

namespace raycache {

class FrameRenderer {
public:
    FrameRenderer(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                  const Parallel& parallel);

    // Fills `film` (resized to the settings' size) with linear radiance and
    // returns the rays traced. The result does not depend on the thread count.
    RayCounts render(const Camera& camera, Image& film) const;

private:
    const Scene& scene_;
    const TraceScene& tracer_;
    RenderSettings settings_;
    const Parallel& parallel_;
    WhittedIntegrator integrator_;
};

}  // namespace raycache
