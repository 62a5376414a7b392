#pragma once
// What caching should gain on a scene, from measured parts of its frames
// (`raycache bench where-caching-pays`, docs/caching.md "When caching pays").
//
// A frame of the uncached renderer takes `uncachedMs`. The same frame with an
// ideal cache, where every ray leaving a caching object is looked up (CCT)
// and never traced, takes `idealMs`; its lookups took `idealLookupMs`. So the
// traced trees of those rays cost
//     trees = uncachedMs - idealMs + idealLookupMs
// per frame. A cache that answers a share `hitRate` of them, its lookups
// costing `lookupMs` a frame, should then take
//     uncachedMs - hitRate * trees + lookupMs.
// Left out, so the model's error shows them: stores and their merge at the
// frame's end, a miss's extra bookkeeping, and the changed coherence of the
// rays still traced.
#include <cstdint>

namespace raycache {

struct CachingPayParts {
    double uncachedMs = 0.0;     // uncached frame, wall ms
    double idealMs = 0.0;        // ideal-cache frame, wall ms
    double idealLookupMs = 0.0;  // the ideal frame's lookups, wall ms (CPU ms over the threads)
    double lookupMs = 0.0;       // the technique's lookups in its own frame, wall ms
    double frameEndMs = 0.0;     // the technique's frame-end work (store merge, pre-fill), wall ms
    double hitRate = 0.0;        // the technique's hits / lookups, 0..1
    std::uint64_t leavingRays = 0;  // rays leaving caching objects per frame (the ideal frame's lookups)
};

// Wall ms per frame spent tracing the trees of rays that leave caching objects.
double cacheableTreeMs(const CachingPayParts& parts);
// cacheableTreeMs over the uncached frame: what an ideal cache could save, at most.
double cacheableShare(const CachingPayParts& parts);
// The frame time the model expects with the technique, and uncached over it.
double predictedFrameMs(const CachingPayParts& parts);
double predictedSpeedup(const CachingPayParts& parts);
// The most any cache could gain: every tree answered, lookups and stores
// free, 1 / (1 - cacheableShare). Infinite when the trees are the whole frame.
double freeCacheSpeedup(const CachingPayParts& parts);

}  // namespace raycache
