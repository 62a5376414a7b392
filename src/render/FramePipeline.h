#pragma once
// How a frame is made (SPEC §4, `--pipeline ray|hybrid`): the ray pipeline
// (FrameRenderer: primary rays as packets, then Whitted shading per pixel) or
// the hybrid pipeline (a G-buffer, by OpenGL or by primary-ray packets, then
// deferred shadow, secondary and composition passes). Both produce the same
// images; the hybrid one also reports its phase times.
#include <memory>
#include <string>

#include "core/Image.h"
#include "core/Parallel.h"
#include "render/FrameStats.h"
#include "render/RenderSettings.h"
#include "scene/Camera.h"
#include "scene/Scene.h"
#include "trace/TraceScene.h"

namespace raycache {

class RayCache;

class FramePipeline {
public:
    virtual ~FramePipeline() = default;
    // Fills `film` (resized to the settings' size) with linear radiance and
    // returns what the frame did. Images and caches do not depend on the
    // thread count. Call from one thread (the hybrid one may own a GL context).
    virtual FrameStats render(const Camera& camera, Image& film) = 0;
    // One line saying which pipeline this is and, for the hybrid one, where
    // its G-buffer comes from and why ("pipeline: hybrid, G-buffer by OpenGL (...)").
    virtual std::string description() const = 0;
};

// The pipeline settings.pipeline asks for. The hybrid pipeline with
// GBufferSource::Auto uses OpenGL when a 4.5 core context can be made and
// primary-ray packets otherwise. Throws RuntimeError when GBufferSource::OpenGl
// is forced and no context can be made. All arguments must outlive the pipeline.
std::unique_ptr<FramePipeline> makeFramePipeline(const Scene& scene, const TraceScene& tracer,
                                                 const RenderSettings& settings, const Parallel& parallel,
                                                 RayCache* cache = nullptr);

}  // namespace raycache
