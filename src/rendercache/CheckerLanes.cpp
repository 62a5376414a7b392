#include "rendercache/CheckerLanes.h"

#include "core/LaneLevels.h"

namespace raycache {

#define RAYCACHE_LANE_KERNELS "rendercache/CheckerLaneKernels.inc"
#include "core/LaneLevelsInclude.h"

void checkerSquares16(const Checkerboard& pattern, const CornerTextureCoordinates& uv, const float* u, const float* v,
                      int* odd) {
    RAYCACHE_LANE_DISPATCH(checkerSquareLanes, pattern, uv, u, v, odd);
}

}  // namespace raycache
