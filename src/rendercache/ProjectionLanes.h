#pragma once
// Reprojection's projection sixteen samples at a time: what projectPoint()
// and imagePixelOf() (rendercache/Reprojection.h) give each sample, lane by
// lane with the same IEEE operations, so the same bits. One sample at a
// time, the two cameras' projections, range tests and floors cost about 120
// instructions a sample, most of reprojection's first round.
#include <cstdint>

#include "core/FloatLanes.h"
#include "core/Vec3.h"
#include "rendercache/SamplePool.h"
#include "rendercache/ScreenProjection.h"

namespace raycache {

// Where sixteen consecutive samples land. Lanes whose `landed` is 0 hold
// nothing meaningful.
struct ProjectedSamples {
    int landed[kFloatLanes];                      // 1 where projectPoint() is true (never for an empty slot)
    float x[kFloatLanes], y[kFloatLanes];         // projectPoint()'s px, py
    float depth[kFloatLanes];                     // and depth
    int pixelX[kFloatLanes], pixelY[kFloatLanes]; // ScreenProjection::pixelOf(px), pixelOf(py)
    std::int32_t nextPixel[kFloatLanes];          // imagePixelOf() through `next` (every lane), when given
};

// The samples points[0, count) (count <= kFloatLanes; the lanes past count
// do not land), whose objects' origins are `origins`, through `projection`
// and, when `next` is given, through it into a width x height image.
void projectSamples16(const SamplePoint* points, int count, const Vec3* origins, const ScreenProjection& projection,
                      const ScreenProjection* next, int width, int height, ProjectedSamples& out);

}  // namespace raycache
