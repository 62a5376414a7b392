#pragma once
#include <optional>

#include "cache/CacheStats.h"
#include "core/RayCounts.h"

namespace raycache {

// What one rendered frame did.
struct FrameStats {
    RayCounts rays;
    std::optional<FrameCacheStats> cache;  // present when caches were in use
};

}  // namespace raycache
