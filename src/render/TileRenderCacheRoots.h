#pragma once
// What the Render Cache's calls of the tile kernel (render/TileKernel.h)
// hand in and take out per root beyond its colour (render/RenderCacheSamples.h):
// a sample's first hit keeps its view-independent light, its light with a white
// albedo and the lights that reach it (PrimarySample); a reshade call gives
// each root's kept light instead of tracing shadow rays (ReshadeRequest).
#include <cstdint>
#include <span>
#include <vector>

#include "core/Rgb.h"
#include "render/HitLanes.h"
#include "render/RenderCacheSamples.h"

namespace raycache {

struct TileRenderCacheRoots {
    // While the first hits are shaded: record their view-independent light.
    bool recordFirstHits = false;
    std::vector<Rgb> rootViewIndependent;
    std::vector<Rgb> rootLighting;  // rootViewIndependent with a white albedo
    std::vector<std::uint64_t> rootLitMask;
    std::span<const ReshadeRequest> reshade;  // the roots of a reshade call, while its first hits are shaded
    std::vector<LightLanes16> reshadeLights;  // per light: a reshaded packet's lights as its lanes see them
};

}  // namespace raycache
