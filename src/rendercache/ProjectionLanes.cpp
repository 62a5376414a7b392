#include "rendercache/ProjectionLanes.h"

#include "core/LaneLevels.h"
#include "core/Rgb.h"
#include "core/Vec3.h"

namespace raycache {

#define RAYCACHE_LANE_KERNELS "rendercache/ProjectionLaneKernels.inc"
#include "core/LaneLevelsInclude.h"

void projectSamples16(const SamplePoint* points, int count, const Vec3* origins, const ScreenProjection& projection,
                      const ScreenProjection* next, int width, int height, ProjectedSamples& out) {
    RAYCACHE_LANE_DISPATCH(projectSampleLanes, points, count, origins, projection, next, width, height, out);
}

}  // namespace raycache
