#pragma once
// The tile kernel's part of the cache-level record (render/CacheLevelImage.h),
// kept only when the caller asks for it: per root, the level of its weightiest
// lookup so far and that lookup's weight, and per lookup of the batch the level
// that answered it. The tile's pixels are written from it at the end.
#include <cstdint>
#include <vector>

namespace raycache {

struct TileCacheLevelRecord {
    bool on = false;  // the callers that record set it after TileScratch::beginTile
    std::vector<std::int8_t> rootLevels;
    std::vector<float> rootLevelWeights;
    std::vector<std::int8_t> answerLevels;
};

}  // namespace raycache
