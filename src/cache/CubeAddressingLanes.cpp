#include "cache/CubeAddressingLanes.h"

#include <cfloat>

#include "core/FloatLanes.h"
#include "core/LaneLevels.h"

namespace raycache {

#define RAYCACHE_LANE_KERNELS "cache/CubeAddressingLaneKernels.inc"
#include "core/LaneLevelsInclude.h"

void cubeTexelIndices16(const float* x, const float* y, const float* z, int size, const int* lanes, int* texels) {
    RAYCACHE_LANE_DISPATCH(cubeTexelIndexLanes, x, y, z, size, lanes, texels);
}

}  // namespace raycache
