#pragma once
#include <optional>

#include "cache/CacheStats.h"
#include "core/RayCounts.h"

namespace raycache {

// Wall time of the hybrid pipeline's phases in one frame, in milliseconds
// (SPEC §4). `raster` is the G-buffer pass: OpenGL drawing, or the
// primary-ray packets of the fallback (whose `readback` is then 0).
struct PhaseTimes {
    double raster = 0.0;
    double readback = 0.0;
    double shadows = 0.0;    // shadow rays of surface pixels and direct light
    double secondary = 0.0;  // reflection/refraction of the pixels that need them
    double compose = 0.0;    // direct + secondary, background where there is no surface
};

// What one rendered frame did.
struct FrameStats {
    RayCounts rays;
    std::optional<FrameCacheStats> cache;  // present when caches were in use
    std::optional<PhaseTimes> phases;      // present for the hybrid pipeline
};

}  // namespace raycache
