#pragma once
// Makes the pipeline a frame asks for (render/FramePipeline.h): it knows
// every pipeline, the ray and hybrid ones (render/) and the Render Cache
// (rendercache/), so it sits above them all.
#include <memory>

#include "core/Parallel.h"
#include "core/ProcessGroup.h"
#include "render/FramePipeline.h"
#include "render/RenderSettings.h"
#include "scene/Scene.h"
#include "trace/TraceScene.h"

namespace raycache {

class RayCache;

// The pipeline settings.pipeline asks for. The hybrid pipeline with
// GBufferSource::Auto uses OpenGL when a 4.5 core context can be made and
// primary-ray packets otherwise. Throws RuntimeError when GBufferSource::OpenGl
// is forced and no context can be made. With `group` of several processes
// only the ray pipeline shares its tiles among them, without the cache-level
// record; the others, and the record, throw InputError. All arguments must
// outlive the pipeline.
std::unique_ptr<FramePipeline> makeFramePipeline(const Scene& scene, const TraceScene& tracer,
                                                 const RenderSettings& settings, const Parallel& parallel,
                                                 RayCache* cache = nullptr, const ProcessGroup* group = nullptr);

}  // namespace raycache
