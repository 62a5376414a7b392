#include "trace/SphereLanes.h"

#include "core/FloatLanes.h"
#include "core/LaneLevels.h"
#include "core/Rgb.h"
#include "core/Vec3.h"

namespace raycache {

#define RAYCACHE_LANE_KERNELS "trace/SphereLaneKernels.inc"
#include "core/LaneLevelsInclude.h"

void sphereRoots16(const Sphere& sphere, const RayLanePointers& rays, const int* active, float* t) {
    RAYCACHE_LANE_DISPATCH(solveLanes, sphere, rays, active, t);
}

}  // namespace raycache
