#pragma once
#include "cache/RayCache.h"

namespace raycache {

// How a frame finds its primary visibility (SPEC §4): primary rays per tile
// (Ray), or a G-buffer followed by deferred shadow and secondary passes (Hybrid).
enum class PipelineKind { Ray, Hybrid };
// Where the hybrid pipeline's G-buffer comes from: OpenGL when a context can
// be made, else primary-ray packets (Auto); or forced either way.
enum class GBufferSource { Auto, OpenGl, Packets };

// What one frame is rendered with. Plain data, passed down explicitly.
struct RenderSettings {
    int width = 512;
    int height = 512;
    // Longest ray path, counting the primary ray as 1: with maxDepth = 1 only
    // primary and shadow rays are traced.
    int maxDepth = 6;
    // A secondary ray is not traced when the product of the kr/kt factors
    // along its path falls below this.
    float minWeight = 0.01f;
    int threads = 0;  // 0 = all hardware threads
    int tileSize = 16;
    // Which objects cache their secondary rays, and how (see RayCache).
    RayCacheSettings cache;
    PipelineKind pipeline = PipelineKind::Ray;
    GBufferSource gbuffer = GBufferSource::Auto;  // hybrid pipeline only
    // Time every stage of the tile kernel (FrameStats::stages): two clock
    // reads per stage and wave, so off unless a profile is wanted.
    bool stageTimes = false;
};

}  // namespace raycache
