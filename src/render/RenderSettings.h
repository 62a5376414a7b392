#pragma once
#include <array>
#include <optional>
#include <string>

#include "cache/RayCache.h"
#include "render/RenderCacheSettings.h"
#include "render/TileAssignment.h"
#include "scene/PipelineKind.h"
#include "trace/TraceScene.h"

namespace raycache {

// Where the hybrid pipeline's G-buffer comes from: OpenGL when a context can
// be made, else primary-ray packets (Auto); or forced either way.
enum class GBufferSource { Auto, OpenGl, Packets };
// Every source, in the order messages and help texts list them.
inline constexpr std::array kGBufferSources{GBufferSource::Auto, GBufferSource::OpenGl, GBufferSource::Packets};
// "auto", "gl", "packets" (`--gbuffer`).
const char* gbufferSourceName(GBufferSource source);

// What one frame is rendered with. Plain data, passed down explicitly.
struct RenderSettings {
    int width = 512;
    int height = 512;
    // Longest ray path, counting the primary ray as 1: with maxDepth = 1 only
    // primary and shadow rays are traced.
    int maxDepth = 6;
    // A secondary ray is not traced when the product of its weights along
    // its path (each weight's largest channel) falls below this.
    float minWeight = 0.01f;
    int threads = 0;  // 0 = all hardware threads
    // Camera rays per pixel (`--spp`, ray pipeline only): 1 is a ray through
    // each pixel's centre; N > 1 stratified jittered rays filtered with
    // Blackman-Harris (render/FilteredFilm.h).
    int samplesPerPixel = 1;
    int tileSize = 16;
    // Which objects cache their secondary rays, and how (see RayCache).
    RayCacheSettings cache;
    PipelineKind pipeline = PipelineKind::Ray;
    GBufferSource gbuffer = GBufferSource::Auto;  // hybrid pipeline only
    RenderCacheSettings renderCache;              // Render Cache pipeline only
    TraceOptions trace;                           // how the tracer follows an animated scene
    // Time every stage of the tile kernel (FrameStats::stages): two clock
    // reads per stage and wave, so off unless a profile is wanted.
    bool stageTimes = false;
    // Record per pixel what the cache did for the pixel's rays leaving
    // caching objects (render/CacheLevelImage.h; the viewer's cube-level
    // overlay). Off, the tile kernel writes nothing per pixel for it. Ray and
    // hybrid pipelines of one process only.
    bool recordCacheLevels = false;
    // How tiles are assigned to the processes of a cluster job (docs/cluster.md).
    TileBalance tileBalance = TileBalance::Dynamic;
};

}  // namespace raycache
