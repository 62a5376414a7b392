#pragma once
// Per pixel, what the cache did for the pixel's ray tree (the viewer's "cube
// level per pixel" overlay, docs/viewer.md): no ray of the tree left a
// caching object; the cache did not answer and the ray was traced; or level
// k of the object's cube answered (0: the finest, 1, 2, ...: coarser levels
// of a multi-resolution CCT cube, cache/CoarseLevels.h; CDCT answers count
// as level 0, as ObjectCacheStats::hitsByLevel counts them).
//
// A tree may ask the caches several times: a glass object's outer reflection
// and the light leaving it again, or a chain of mirrors whose first lookup
// was traced. The record keeps the lookup whose ray weighs most in the pixel
// (the product of its weights along its path), the first asked on equal weight:
// the one whose answer makes most of what the pixel shows. Along a chain of
// mirrors the weights only shrink, so that is the first mirror's lookup; for
// glass it is the refracted light leaving the object, not the faint outer
// reflection asked before it.
//
// Made only when RenderSettings::recordCacheLevels asks for it.
#include <array>
#include <cstdint>
#include <vector>

#include "cache/CacheStats.h"

namespace raycache {

class CacheLevelImage {
public:
    static constexpr std::int8_t kNoCachingRay = -2;  // no ray of the pixel's tree left a caching object
    static constexpr std::int8_t kTraced = -1;        // the cache did not answer (invalid texel, rejected): traced
    // Pixels per record value: [0] no caching ray, [1] traced, [2 + k] answered by level k.
    using Counts = std::array<std::int64_t, kMaxCubeLevels + 2>;

    CacheLevelImage() = default;
    // Every pixel kNoCachingRay.
    CacheLevelImage(int width, int height)
        : width_(width), height_(height),
          values_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), kNoCachingRay) {}

    int width() const { return width_; }
    int height() const { return height_; }
    // Row-major, row 0 at the top, as the film.
    const std::vector<std::int8_t>& values() const { return values_; }
    std::int8_t at(int x, int y) const { return values_[index(x, y)]; }
    std::int8_t& at(int x, int y) { return values_[index(x, y)]; }

    // How many pixels hold each value (see Counts).
    Counts counts() const {
        Counts c{};
        for (const std::int8_t v : values_) ++c[static_cast<std::size_t>(v + 2)];
        return c;
    }

private:
    std::size_t index(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
    }
    int width_ = 0;
    int height_ = 0;
    std::vector<std::int8_t> values_;
};

}  // namespace raycache
