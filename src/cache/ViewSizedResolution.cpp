#include "cache/ViewSizedResolution.h"

#include <algorithm>

#include "cache/CoarseLevels.h"

namespace raycache {

ViewSizedResolution::ViewSizedResolution(int fullSize) : fullSize_(fullSize) {
    // Exact halvings only: a texel at size n/2 then covers exactly 2×2 texels
    // at size n (cube addressing floors s·n, and s·n/2 is exact in float).
    const int floor = std::min(kMinSize, fullSize);
    while (coarsestLevel_ + 1 < kMaxCubeLevels && (fullSize >> (coarsestLevel_ + 1)) >= floor &&
           ((fullSize >> (coarsestLevel_ + 1)) << (coarsestLevel_ + 1)) == fullSize)
        ++coarsestLevel_;
}

int ViewSizedResolution::levelAllowed(float spread, float errorBound) const {
    return CoarseLevels::coarsestAllowed(spread, errorBound, fullSize_, coarsestLevel_ + 1);
}

int ViewSizedResolution::afterFrame(const LookupsByLevel& lookups) {
    std::uint64_t total = 0;
    for (const std::uint64_t n : lookups) total += n;
    if (total == 0) return level_;  // not looked at: nothing to go by
    // The coarsest level leaving at most kUnderservedShare of the lookups
    // wanting a finer one.
    const auto allowedUnderserved = static_cast<std::uint64_t>(kUnderservedShare * static_cast<double>(total));
    int wanted = 0;
    std::uint64_t underserved = 0;
    while (wanted < coarsestLevel_) {
        underserved += lookups[static_cast<std::size_t>(wanted)];
        if (underserved > allowedUnderserved) break;
        ++wanted;
    }
    if (!decided_ || wanted < level_) {
        decided_ = true;
        level_ = wanted;
        coarserFrames_ = 0;
    } else if (wanted > level_) {
        coarserWanted_ = coarserFrames_ == 0 ? wanted : std::min(coarserWanted_, wanted);
        if (++coarserFrames_ >= kFramesBeforeCoarser) {
            level_ = coarserWanted_;
            coarserFrames_ = 0;
        }
    } else {
        coarserFrames_ = 0;
    }
    return level_;
}

}  // namespace raycache
