#pragma once
// Checks a cache's invalidation against the truth (docs/dynamic-scenes.md):
// before a change of an animated scene, take() records every valid texel
// with the ray it was stored for; after it, check() traces each of those
// rays again in the new pose without caches and compares bit for bit.
//   stale:    kept, but its ray now brings back something else (must be 0);
//   needless: dropped, but its ray still brings back the same colour.
// Needs a session whose caches run with RayCacheSettings::invalidationOracle,
// where every lookup misses, so each stored colour is its ray's uncached colour.
#include <cstdint>
#include <vector>

#include "session/RenderSession.h"

namespace raycache {

struct InvalidationCounts {
    std::int64_t checked = 0;   // texels valid before the change
    std::int64_t kept = 0, stale = 0;
    std::int64_t dropped = 0, needless = 0;
    // Texels whose colour the change really altered.
    std::int64_t changed() const { return stale + (dropped - needless); }
    std::int64_t differing = 0;  // texels whose re-trace differed in their own pose (the oracle failing itself)
    // Of those, the ones off by more than kTolerance in some channel (texels
    // filled from visible surfaces, render/VisibleSurfaceFill.h, differ within
    // rounding where the fill is exact).
    std::int64_t differingBeyondTolerance = 0;
    // Texels of caching objects that moved (their cube follows them; these
    // are re-traced from their origin moved along): how many there were, and
    // how many would still be within kTolerance of the truth if kept.
    // Of those, how many the cache kept (rays escaping to the environment
    // that still do, moved along with their sphere).
    std::int64_t movedCube = 0, movedCubeWithinTolerance = 0, movedCubeKept = 0;
    static constexpr float kTolerance = 1.0f / 255.0f;  // per channel, linear

    InvalidationCounts& operator+=(const InvalidationCounts& o);
};

class InvalidationOracle {
public:
    // Records the session's valid texels and re-traces them in the current
    // pose (counted in `differing` if that does not give the stored colour).
    void take(const RenderSession& session);
    // The texels take() found differing, in all and beyond kTolerance.
    std::int64_t differing() const { return differing_; }
    std::int64_t differingBeyondTolerance() const { return differingBeyondTolerance_; }
    // Valid texels take() recorded.
    std::size_t texelCount() const { return texels_.size(); }
    // After session.setTime(): what happened to the recorded texels.
    InvalidationCounts check(const RenderSession& session) const;

private:
    struct StoredTexel {
        int objectId;
        int texel;
        std::uint32_t word;
        RayTreeRecord tree;
    };
    std::vector<std::uint32_t> retrace(const RenderSession& session) const;

    std::vector<StoredTexel> texels_;
    std::vector<Vec3> cubeCenters_;  // per object id (caching objects only), when taken
    std::int64_t differing_ = 0;
    std::int64_t differingBeyondTolerance_ = 0;
};

}  // namespace raycache
