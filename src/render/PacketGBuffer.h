#pragma once
// The hybrid pipeline's G-buffer without OpenGL: primary rays per tile traced
// as coherent packets, each hit written in the G-buffer layout
// (raster/GBuffer.h), exactly the surface the ray pipeline would shade.
#include <cstdint>

#include "core/Parallel.h"
#include "raster/GBuffer.h"
#include "scene/Camera.h"
#include "scene/Scene.h"
#include "trace/TraceScene.h"

namespace raycache {

class PacketGBuffer {
public:
    PacketGBuffer(const Scene& scene, const TraceScene& tracer, const Parallel& parallel, int tileSize);

    // Fills `out` with what `camera` sees at width x height and returns the
    // number of primary rays traced.
    std::uint64_t fill(const Camera& camera, int width, int height, GBufferStorage& out) const;

private:
    const Scene& scene_;
    const TraceScene& tracer_;
    const Parallel& parallel_;
    int tileSize_;
};

}  // namespace raycache
