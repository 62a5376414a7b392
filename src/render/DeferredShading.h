#pragma once
// The deferred passes of the hybrid pipeline (SPEC §4 steps 2-4), shared by
// both G-buffer producers: shadow rays only for pixels that hold a surface,
// reflection/refraction rays only for pixels whose material needs them
// (traced by the same integrator and answered by the same caches as in the
// ray pipeline), then composition into the film.
#include <vector>

#include "core/Image.h"
#include "core/Parallel.h"
#include "render/FrameStats.h"
#include "render/GBuffer.h"
#include "render/RenderSettings.h"
#include "render/WhittedIntegrator.h"
#include "scene/Camera.h"

namespace raycache {

// The surface the ray pipeline would have built from the same hit: position
// and shading normal from the G-buffer, the triangle's geometric normal, and
// both turned toward the camera. Texture coordinates are not rebuilt (the
// G-buffer carries the albedo). Pixel i must hold a surface.
SurfacePoint surfacePointFromGBuffer(const Scene& scene, const GBufferView& gbuffer, std::size_t i,
                                     const Vec3& rayDirection);

class DeferredShading {
public:
    // With `cache` (may be null), caching objects' secondary rays go through
    // it, and its frame hooks run around every frame's secondary pass.
    DeferredShading(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                    const Parallel& parallel, RayCache* cache);

    // Shades the frame `camera` sees from `gbuffer` (the settings' size) into
    // `film`; adds its rays to stats.rays, sets stats.cache and the shadows,
    // secondary and compose times of stats.phases (the three run per tile in
    // one parallel pass, whose wall time is split in proportion to the time
    // the workers spent in each; the cache merge counts as secondary).
    // Images and caches do not depend on the thread count.
    void shade(const Camera& camera, const GBufferView& gbuffer, Image& film, FrameStats& stats);

private:
    const Scene& scene_;
    const TraceScene& tracer_;
    RenderSettings settings_;
    const Parallel& parallel_;
    RayCache* cache_;
    WhittedIntegrator integrator_;
    std::vector<unsigned char> needsSecondary_;  // per object: reflects or refracts, and depth allows it
};

}  // namespace raycache
