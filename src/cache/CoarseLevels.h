#pragma once
// The coarser levels of a CCT caching cube (docs/caching.md, "Multi-resolution
// cubes"): level k has ceil(n / 2^k) texels per face side, and its texel
// (face, x >> k, y >> k) covers the 2^k x 2^k texels (face, x, y) of the
// finest level n. A store to a finest texel also fills every coarser texel
// over it that is still invalid, with its colour and with what its ray saw:
// the point it hit, or its direction when it met nothing. A coarse texel
// therefore fills 4^k times faster than a finest one, but it stands for
// rays of many directions from many points of the object, and CCT's
// addressing by direction alone would answer them all with one colour. So a
// coarse texel only answers a ray that would see (nearly) the same point:
// RayCache::lookupBatch takes the finest level whose texel is no wider than
// the ray's pixel footprint allows (coarsestAllowed) and whose stored point
// lies within that footprint of the ray (seesWithin).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "cache/CacheStats.h"
#include "cache/CachingCube.h"

namespace raycache {

// What a stored ray saw: a point (w = 1), or a direction to infinity (w = 0).
struct SeenPoint {
    Vec3 v;
    float w = 0.0f;
};

class CoarseLevels {
public:
    // Levels of a cube, the finest included: at most this many.
    static constexpr int kMaxLevels = kMaxCubeLevels;
    // A coarse level is kept only while its faces have at least this many
    // texels per side (a 90-degree face in fewer texels answers little).
    static constexpr int kMinSize = 4;

    // No coarser level (a single-resolution cube).
    CoarseLevels() = default;
    // Up to levels - 1 coarser levels below a finest level of `finestSize`
    // (fewer when they would drop below kMinSize); all texels invalid.
    CoarseLevels(const Vec3& center, int finestSize, int levels);

    // The coarsest level a lookup may read (0: only the finest): the widest
    // whose texels, seen from the cube's centre, span at most `errorBound`
    // times `spread`, the angle between the rays of neighbouring pixels
    // where the looked-up ray leaves the object (its cone's spread). A face
    // texel of side s spans at most 2s / n radians (at the face's centre).
    static int coarsestAllowed(float spread, float errorBound, int finestSize, int levelCount);
    // Whether a ray from `origin` along unit `direction` sees `seen` within
    // `maxAngle` radians (taken as at most 1.5) of its direction.
    static bool seesWithin(const SeenPoint& seen, const Vec3& origin, const Vec3& direction, float maxAngle);
    // The same test with the angle given by its tangent (>= 0), for callers
    // testing one ray against several levels.
    static bool seesWithinTangent(const SeenPoint& seen, const Vec3& origin, const Vec3& direction, float tangent) {
        // The stored ray's point as seen from this ray's origin (its direction
        // alone when it met nothing: a point at infinity looks the same from anywhere).
        const Vec3 toSeen = seen.w != 0.0f ? seen.v - origin : seen.v;
        const float along = dot(toSeen, direction);
        if (!(along > 0.0f)) return false;
        // tan(angle) = |toSeen x direction| / along.
        const Vec3 aside = cross(toSeen, direction);
        return dot(aside, aside) <= tangent * tangent * along * along;
    }

    // Levels in all, the finest included (1: none coarser).
    int levelCount() const { return static_cast<int>(levels_.size()) + 1; }
    // Level `level` in [1, levelCount()).
    const CachingCube& level(int level) const { return levels_[static_cast<std::size_t>(level - 1)]; }
    // What the ray stored in texel `texel` of level `level` saw (valid texels).
    const SeenPoint& seen(int level, int texel) const {
        return seen_[static_cast<std::size_t>(level - 1)][static_cast<std::size_t>(texel)];
    }
    // The texel of level `level` over finest texel `finestTexel`.
    int texelOver(int finestTexel, int level) const;
    // The same for the finest texel (face, x, y), without divisions.
    int texelOver(int face, int x, int y, int level) const {
        const int size = levels_[static_cast<std::size_t>(level - 1)].size();
        return (face * size + (y >> level)) * size + (x >> level);
    }
    // Fills every coarser texel over `finestTexel` that is still invalid with
    // `packed` and `seen`; returns how many it wrote.
    int writeOver(int finestTexel, std::uint32_t packed, const SeenPoint& seen);
    // Invalidates every coarser texel over the finest texels [x0, x1) x
    // [y0, y1) of face `face`; returns how many were valid.
    std::int64_t dropOver(int face, int x0, int y0, int x1, int y1);
    void clear();
    void moveTo(const Vec3& center);
    std::size_t bytes() const;
    std::size_t validCount() const;

private:
    int finestSize_ = 0;
    std::vector<CachingCube> levels_;          // level k at [k - 1]
    std::vector<std::vector<SeenPoint>> seen_;  // level k at [k - 1], per texel
};

}  // namespace raycache
