#pragma once
// What every rendering command needs before its first frame: a loaded scene,
// the camera path, the render settings and the frame count, from the options
// those commands share (scene, size, frames, path, threads, depth, caching).
#include <array>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>

#include "cache/CachePolicy.h"
#include "core/DisplayTransform.h"
#include "render/RenderSettings.h"
#include "scene/CameraPath.h"
#include "scene/Scene.h"
#include "session/FrameLoop.h"

namespace raycache {

// The camera paths RenderJobOptions::path may ask for: those made from the
// scene's own camera (keyframes come from a scene file).
inline constexpr std::array kPathOptionKinds{CameraPathKind::Static, CameraPathKind::Orbit, CameraPathKind::Pan};

struct RenderJobOptions {
    std::string scene = "room";
    bool blinnPhongGltfMaterials = false;  // --gltf-materials blinn-phong
    int width = 512;
    int height = 512;
    std::optional<int> frames;        // default: the scene's path length
    std::optional<CameraPathKind> path;  // one of kPathOptionKinds; default: the scene's own path
    float time = 0.0f;                // seconds of an animated scene the first frame shows
    std::optional<float> fps;         // frames per second of animation time; default: the scene's
    int threads = 0;
    int samplesPerPixel = 1;              // --spp: camera rays per pixel (RenderSettings::samplesPerPixel)
    std::optional<float> exposure;        // stops; default: the scene file's, else 0
    std::optional<ViewTransform> viewTransform;  // default: the scene file's, else standard
    int maxDepth = 6;
    float minWeight = 0.01f;
    std::optional<CacheTechnique> technique;  // default: each material's own setting
    std::optional<float> cdctStep;         // CDCT search parameters; default: each material's own
    std::optional<float> cdctEpsilon;
    std::optional<float> cdctMaxDepth;
    std::optional<float> cdctTolerance;    // improved CDCT error control, texels
    // RayCacheSettings::prefillTexelsPerFrame; default: 0 (whole cubes at
    // once), but half the image's pixels a frame in the viewer.
    std::optional<std::int64_t> cdctPrefillPerFrame;
    std::optional<int> cacheResolution;    // default: each material's own setting
    int cacheLevels = 1;                   // CCT cubes' resolution levels (RayCacheSettings::cubeLevels)
    float cacheLevelError = 0.25f;         // RayCacheSettings::levelErrorBound
    bool cacheResFromView = false;         // RayCacheSettings::resolutionFromView
    VisibleFill cacheFill = VisibleFill::Off;  // RayCacheSettings::visibleFill
    std::optional<double> cacheBudgetMiB;  // cubes' memory budget; default: the scene file's, else half the machine's memory
    bool cacheIdeal = false;               // benchmark switch, see RayCacheSettings::ideal
    bool cacheStoreChanging = false;       // RayCacheSettings::skipStoresReachingChanges off
    CachePolicyMode cachePolicy = CachePolicyMode::Auto;  // RayCacheSettings::policy
    bool stageTimes = false;               // time the tile kernel's stages (RenderSettings::stageTimes)
    std::optional<PipelineKind> pipeline;  // default: the scene file's, else ray
    std::optional<Accelerator> accel;      // default: the scene file's, else embree
    GBufferSource gbuffer = GBufferSource::Auto;     // the hybrid pipeline's G-buffer
    TileBalance tileBalance = TileBalance::Dynamic;  // MPI jobs' tile assignment (docs/cluster.md)
    // The Render Cache's --rc-* options; default: the scene file's, else RenderCacheSettings'.
    RenderCacheOverrides renderCache;
};

struct RenderJob {
    Scene scene;
    CameraPath path;
    FrameTimeline timeline;  // the moment of the animation each frame shows
    RenderSettings settings;
    DisplaySettings display;  // how 8-bit images and the viewer show the film
    int frames = 1;
    std::string cacheBudgetNote;  // what the cubes' memory budget lowered (RayCache::budgetNote), or empty
};

// Puts the values that are set into `settings`.
void applyRenderCacheOverrides(const RenderCacheOverrides& overrides, RenderCacheSettings& settings);

// Throws InputError for option values out of range, without touching the
// scene, so commands can check their own options in between and still report
// errors in a fixed order.
void validateRenderJobOptions(const RenderJobOptions& options);

// Validates the options (as validateRenderJobOptions), loads the scene and
// resolves the camera path, settings and frame count. Throws InputError for
// bad options or scene input; renders nothing.
RenderJob prepareRenderJob(const RenderJobOptions& options);

// What loading repaired or left out of the scene (Scene::notes), one
// "note: ..." line each.
void printSceneNotes(const Scene& scene, std::ostream& out);

}  // namespace raycache
