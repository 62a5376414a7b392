#pragma once
// How a frame is made (`--pipeline ray|hybrid|render-cache`): the ray
// pipeline (FrameRenderer: primary rays as packets, then Whitted shading per
// pixel); the hybrid pipeline (Ruff et al. 2013: a G-buffer, by OpenGL or by
// primary-ray packets, then deferred shadow, secondary and composition
// passes), which gives the ray pipeline's images and reports its phase
// times; or the Render Cache (rendercache/RenderCachePipeline.h),
// which reuses reprojected samples and traces only some pixels per frame.
#include <memory>
#include <string>

#include "core/Errors.h"
#include "core/Image.h"
#include "core/Parallel.h"
#include "core/ProcessGroup.h"
#include "render/FrameStats.h"
#include "render/RenderSettings.h"
#include "scene/Camera.h"
#include "scene/Scene.h"
#include "scene/ScenePose.h"
#include "trace/TraceScene.h"

namespace raycache {

class CacheLevelImage;
class PixelSamples;
class RayCache;
struct RenderCacheOverlays;

class FramePipeline {
public:
    virtual ~FramePipeline() = default;
    // Fills `film` (resized to the settings' size) with linear radiance and
    // returns what the frame did. Images and caches do not depend on the
    // thread count. Call from one thread (the hybrid one may own a GL context).
    virtual FrameStats render(const Camera& camera, Image& film) = 0;
    // Fills `layer` with one jittered sample layer (render/PixelSamples.h):
    // pixel (x, y)'s ray through samples.offset(x, y, sample). What `--spp N`
    // gathers N of (render/FilteredFilm.h), and what the viewer refines a
    // still view with. Only the ray pipeline renders layers: RuntimeError
    // elsewhere.
    virtual FrameStats renderSample(const Camera& camera, Image& layer, const PixelSamples& samples, int sample) {
        (void)camera, (void)layer, (void)samples, (void)sample;
        throw RuntimeError(description() + " renders one ray per pixel; sample layers need the ray pipeline");
    }
    // One line saying which pipeline this is and, for the hybrid one, where
    // its G-buffer comes from and why ("pipeline: hybrid, G-buffer by OpenGL (...)").
    virtual std::string description() const = 0;
    // The Render Cache pipeline's maps of its last frame, for the viewer's
    // overlays; null for the other pipelines.
    virtual const RenderCacheOverlays* renderCacheOverlays() const { return nullptr; }
    // The last frame's cache-level record (render/CacheLevelImage.h) when
    // RenderSettings::recordCacheLevels asked for it; null otherwise, and
    // always for the Render Cache pipeline, which does not make one.
    virtual const CacheLevelImage* cacheLevels() const { return nullptr; }
    // The scene this pipeline renders moved (RenderSession::setTime); the
    // tracer and the caches are already updated. Pipelines that keep their
    // own copy of geometry (the hybrid one's OpenGL buffers) update it.
    virtual void sceneChanged(const SceneChanges& changes) { (void)changes; }
};

// Pipelines are made by session/PipelineFactory.h, which knows them all.

}  // namespace raycache
