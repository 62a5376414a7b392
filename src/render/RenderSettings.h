#pragma once
#include "cache/RayCache.h"

namespace raycache {

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
};

}  // namespace raycache
