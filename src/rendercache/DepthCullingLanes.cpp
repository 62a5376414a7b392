#include "core/FloatLanes.h"
#include "core/LaneLevels.h"
#include "rendercache/DepthCulling.h"

namespace raycache {

#define RAYCACHE_LANE_KERNELS "rendercache/DepthCullingLaneKernels.inc"
#include "core/LaneLevelsInclude.h"

void hiddenByNearerKeysRow(const std::uint32_t* above, const std::uint32_t* row, const std::uint32_t* below, int count,
                           float threshold, unsigned char* hidden) {
    RAYCACHE_LANE_DISPATCH(hiddenByNearerKeysRowLanes, above, row, below, count, threshold, hidden);
}

}  // namespace raycache
