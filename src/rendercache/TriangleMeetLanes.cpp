#include "rendercache/TriangleMeetLanes.h"

#include "core/LaneLevels.h"

namespace raycache {

#define RAYCACHE_LANE_KERNELS "rendercache/TriangleMeetLaneKernels.inc"
#include "core/LaneLevelsInclude.h"

void meetTriangle16(const TriangleOnItsPlane& triangle, const RayLanes16& rays, TriangleMeets16& out) {
    RAYCACHE_LANE_DISPATCH(meetTriangleLanes, triangle, rays, out);
}

}  // namespace raycache
