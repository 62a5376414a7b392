#pragma once
// Resolution from the view (RayCacheSettings::resolutionFromView,
// docs/caching.md "Resolution from the view"): a CCT cube's face resolution
// follows the rays that look it up, so a small or far mirror does not keep
// (and fill) 512² faces its pixels cannot resolve.
//
// Each lookup carries its ray's footprint (RayCache::Query::spread, the angle
// between neighbouring pixels' rays where it leaves the object). A face of n
// texels serves a lookup within the cache's error bound while its texels
// span at most bound × spread (the same rule that lets a coarser level answer,
// CoarseLevels::coarsestAllowed). After every frame the cube takes the
// coarsest resolution that serves all but 1 % of that frame's lookups: at
// once when that is finer than now, and only after kFramesBeforeCoarser
// frames in a row asked for coarser (an object passing by does not lose its
// texels to one frame's view). Resolutions are the full one (asked, after
// the memory budget) halved 0, 1, 2... times, never below kMinSize (or the
// full one when that is smaller). Deterministic: the decision reads counts only.
#include <array>
#include <cstdint>

#include "cache/CacheStats.h"

namespace raycache {

class ViewSizedResolution {
public:
    static constexpr int kMinSize = 16;
    static constexpr int kFramesBeforeCoarser = 4;
    // Lookups served badly by the chosen resolution: at most this share.
    static constexpr double kUnderservedShare = 0.01;
    // Per level below the full resolution (0: full), how many lookups of a
    // frame allowed at most that level.
    using LookupsByLevel = std::array<std::uint64_t, kMaxCubeLevels>;

    ViewSizedResolution() = default;
    // A cube of `fullSize` texels per face side, starting at full size.
    explicit ViewSizedResolution(int fullSize);

    int fullSize() const { return fullSize_; }
    int level() const { return level_; }
    int size() const { return fullSize_ >> level_; }
    int coarsestLevel() const { return coarsestLevel_; }
    // The coarsest level whose texels still serve a lookup of `spread`
    // within `errorBound` (0 for spread 0: only the full resolution).
    int levelAllowed(float spread, float errorBound) const;
    // After a frame whose lookups allowed `lookups`: the level to take now.
    int afterFrame(const LookupsByLevel& lookups);

private:
    int fullSize_ = 0;
    int level_ = 0;
    int coarsestLevel_ = 0;
    bool decided_ = false;   // a frame with lookups has chosen once
    int coarserFrames_ = 0;  // frames in a row that wanted a coarser level
    int coarserWanted_ = 0;  // the finest level those frames wanted
};

}  // namespace raycache
