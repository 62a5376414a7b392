#pragma once
// The hybrid pipeline's G-buffer by rasterization (its first step): OpenGL 4.5
// core draws the scene into multiple render targets (position + ray distance,
// normal, albedo, object/primitive id, depth) and reads them back once per
// frame into a persistently mapped pixel buffer, which the deferred passes
// then read in place (layout: raster/GBuffer.h).
//
// Triangles are drawn as they are. Spheres are ray-cast impostors: the back
// faces of each sphere's bounding box are rasterized and the fragment shader
// intersects the pixel's camera ray with the analytic sphere, so spheres
// cover exactly the pixels whose centre ray hits them, as in the tracer.
// Depth is the distance along the pixel's camera ray (the tracer's t), so
// raster and tracer agree on which surface is nearest.
#include <memory>
#include <span>
#include <string>

#include "raster/GBuffer.h"
#include "scene/Camera.h"
#include "scene/Scene.h"

namespace raycache {

class GlContext;

// Wall time of the two GL phases of one frame, in milliseconds.
struct RasterTimes {
    double raster = 0.0;    // drawing the G-buffer, until the GL has finished it
    double readback = 0.0;  // copying it into the mapped buffer, until it is readable
};

class GBufferRasterizer {
public:
    // Makes an OpenGL 4.5 core context (current on the calling thread) and
    // uploads the scene's geometry and textures; null with `whyNot` set when
    // no such context can be made. All later calls must come from one thread.
    static std::unique_ptr<GBufferRasterizer> create(const Scene& scene, std::string& whyNot);
    ~GBufferRasterizer();
    GBufferRasterizer(const GBufferRasterizer&) = delete;
    GBufferRasterizer& operator=(const GBufferRasterizer&) = delete;

    // Draws the G-buffer of `camera` at width x height and reads it back. The
    // view stays valid until the next call or the rasterizer's destruction.
    // Throws RuntimeError if OpenGL fails.
    GBufferView rasterize(const Camera& camera, int width, int height, RasterTimes& times);

    // Uploads again the meshes of objects `changed` and the scene's bounds,
    // after the scene given to create() moved (scene/ScenePose.h).
    void sceneChanged(std::span<const int> changed);

    // The context it draws with, e.g. "EGL 1.5 surfaceless (no surface), OpenGL 4.5 ..., llvmpipe ...".
    const std::string& description() const;

private:
    struct Impl;
    explicit GBufferRasterizer(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace raycache
