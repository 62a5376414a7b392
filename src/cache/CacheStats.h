#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "cache/CachePolicy.h"

namespace raycache {

// Resolution levels a CCT cube may keep (cache/CoarseLevels.h), the finest included.
inline constexpr int kMaxCubeLevels = 8;

// CDCT searches counted by the texels they sampled: fewer than 4, 16, 64,
// 256, 1024, and 1024 or more (a cost that grows with the face resolution
// shows as a shift to the right).
inline constexpr int kCdctStepBuckets = 6;
inline int cdctStepBucket(std::uint64_t steps) {
    int bucket = 0;
    for (std::uint64_t limit = 4; bucket < kCdctStepBuckets - 1 && steps >= limit; limit *= 4) ++bucket;
    return bucket;
}

// One caching object's activity during one frame.
struct ObjectCacheStats {
    int objectId = -1;
    std::string name;
    int resolution = 0;                 // texels per face side during the frame
    // Resolution from the view: the resolution the cube took after the
    // frame, 0 when it kept its own.
    int resizedTo = 0;
    std::uint64_t lookups = 0;          // secondary rays that asked the cache
    std::uint64_t hits = 0;             // answered from a valid texel
    // Of the hits, how many each level answered (0: the finest; CCT cubes
    // with coarser levels, RayCacheSettings::cubeLevels); others count at 0.
    std::array<std::uint64_t, kMaxCubeLevels> hitsByLevel{};
    int levels = 1;                     // resolution levels of the cube, the finest included
    std::uint64_t misses = 0;           // not answered (invalid texel, CDCT search gave up or rejected): traced
    std::uint64_t rejected = 0;         // of the misses: improved-CDCT error control found the texel off the ray
    // Of the misses: improved CDCT, rays that meet their own object (a
    // concave mirror seeing itself), which its cube does not hold: traced.
    std::uint64_t ownSurface = 0;
    // Of the misses: improved CDCT, rays whose search met a texel that saw a
    // mirror or glass from the centre (view-dependent colour): traced.
    std::uint64_t viewDependent = 0;
    // CDCT: searches of the cube's depths, the texels they sampled in all
    // (march and bisection steps), and the searches by steps (cdctStepBucket).
    std::uint64_t cdctSearches = 0;
    std::uint64_t cdctSteps = 0;
    std::array<std::uint64_t, kCdctStepBuckets> cdctStepsHistogram{};
    std::uint64_t stores = 0;           // texels written at the end of the frame
    // Stores not made: their ray tree reached what the last scene change
    // moved (RayCacheSettings::skipStoresReachingChanges).
    std::uint64_t skippedStores = 0;
    std::uint64_t prefilledTexels = 0;  // improved CDCT: texels filled from the centre after this frame
    double invalidPercentBefore = 0.0;  // invalid texels when the frame started
    std::size_t bytes = 0;              // memory of the cube's texels (all levels)
    // The cache policy (cache/CachePolicy.h, --cache-policy): what the cube
    // did during this frame (cached; sampled, looking up the rays of 1 in 16
    // runs of texels; or stood aside, its rays traced directly) and will do
    // during the next.
    CubeState state = CubeState::Caching;
    CubeState next = CubeState::Caching;
    std::uint64_t bypassedRays = 0;     // rays that left the object while it stood aside or out of its sample: traced
    std::uint64_t framesCaching = 0;    // frames so far in each state, this one included
    std::uint64_t framesSampling = 0;
    std::uint64_t framesBypassed = 0;
    std::uint64_t queuedStores = 0;     // stores asked for this frame (before merge)
    // Animated scenes: tests of the cube's blocks against the regions the
    // change before this frame reached (CubeFrameCounts::regionTests).
    std::uint64_t regionTests = 0;
    double meanTree = 0.0;              // rays of the traced tree a hit replaces (the last frame that traced one)
    // The policy's model of this frame, in traced rays: what the hits spared
    // and what the lookups, stores and searches cost (0 when bypassed).
    double policySaving = 0.0;
    double policyCost = 0.0;
};

struct FrameCacheStats {
    std::vector<ObjectCacheStats> objects;
    // Every cube stood aside during the frame, so it was rendered exactly as
    // without a cache (render/CacheFrame.h): no lookups, no stores, and the
    // rays leaving the cubes' objects were not counted (bypassedRays 0).
    bool tracedAsUncached = false;

    std::uint64_t lookups() const { return sum(&ObjectCacheStats::lookups); }
    std::uint64_t hits() const { return sum(&ObjectCacheStats::hits); }
    std::uint64_t misses() const { return sum(&ObjectCacheStats::misses); }
    std::uint64_t stores() const { return sum(&ObjectCacheStats::stores); }
    std::uint64_t skippedStores() const { return sum(&ObjectCacheStats::skippedStores); }
    std::uint64_t rejected() const { return sum(&ObjectCacheStats::rejected); }
    std::uint64_t ownSurface() const { return sum(&ObjectCacheStats::ownSurface); }
    std::uint64_t viewDependent() const { return sum(&ObjectCacheStats::viewDependent); }
    std::uint64_t cdctSearches() const { return sum(&ObjectCacheStats::cdctSearches); }
    std::uint64_t cdctSteps() const { return sum(&ObjectCacheStats::cdctSteps); }
    std::uint64_t prefilledTexels() const { return sum(&ObjectCacheStats::prefilledTexels); }
    std::uint64_t bypassedRays() const { return sum(&ObjectCacheStats::bypassedRays); }
    int cubesIn(CubeState state) const {
        int n = 0;
        for (const auto& o : objects) n += o.state == state ? 1 : 0;
        return n;
    }
    int bypassedCubes() const { return cubesIn(CubeState::Bypassed); }
    int samplingCubes() const { return cubesIn(CubeState::Sampling); }
    std::uint64_t hitsAtLevel(int level) const {
        std::uint64_t s = 0;
        for (const auto& o : objects) s += o.hitsByLevel[static_cast<std::size_t>(level)];
        return s;
    }
    // The most levels any cube has.
    int levels() const {
        int most = 1;
        for (const auto& o : objects) most = o.levels > most ? o.levels : most;
        return most;
    }
    std::size_t bytes() const {
        std::size_t b = 0;
        for (const auto& o : objects) b += o.bytes;
        return b;
    }
    // Invalid texels over all cubes when the frame started, in percent.
    double invalidPercentBefore() const {
        double weighted = 0.0, texels = 0.0;
        for (const auto& o : objects) {
            const double n = 6.0 * o.resolution * o.resolution;
            weighted += o.invalidPercentBefore * n;
            texels += n;
        }
        return texels > 0.0 ? weighted / texels : 0.0;
    }

private:
    std::uint64_t sum(std::uint64_t ObjectCacheStats::*field) const {
        std::uint64_t s = 0;
        for (const auto& o : objects) s += o.*field;
        return s;
    }
};

}  // namespace raycache
