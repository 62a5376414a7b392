#pragma once
// TriangleOnItsPlane::meet (render/HitOnPrimitive.h) for sixteen rays at
// once, lane by lane with the same IEEE operations (the same bits): the
// texture re-fetch of a row's textured samples meets their centre rays
// with mostly one triangle, and one ray at a time cost ~90 instructions.
#include "core/FloatLanes.h"
#include "render/HitOnPrimitive.h"
#include "trace/RayPacket.h"

namespace raycache {

struct TriangleMeets16 {
    int hit[kFloatLanes];                 // 1 where meet() is true
    float u[kFloatLanes], v[kFloatLanes]; // meet()'s barycentrics, where `hit`
};

// meet(ray k of `rays`) for every k < 16, for a valid `triangle`.
void meetTriangle16(const TriangleOnItsPlane& triangle, const RayLanes16& rays, TriangleMeets16& out);

}  // namespace raycache
