#include "trace/SphereLanes.h"

#include "core/FloatLanes.h"
#include "core/LaneLevels.h"

namespace raycache {

#if !defined(RAYCACHE_BASELINE_LANES)
#define RAYCACHE_LANE_LEVEL avx512
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v4")
#include "trace/SphereLaneKernels.inc"
#pragma GCC pop_options
#undef RAYCACHE_LANE_LEVEL

#define RAYCACHE_LANE_LEVEL avx2
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v3")
#include "trace/SphereLaneKernels.inc"
#pragma GCC pop_options
#undef RAYCACHE_LANE_LEVEL
#endif

#define RAYCACHE_LANE_LEVEL baseline
#include "trace/SphereLaneKernels.inc"
#undef RAYCACHE_LANE_LEVEL

void sphereRoots16(const Sphere& sphere, const RayLanePointers& rays, const int* active, float* t) {
    RAYCACHE_LANE_DISPATCH(solveLanes, sphere, rays, active, t);
}

}  // namespace raycache
