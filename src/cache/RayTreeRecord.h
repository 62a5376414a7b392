#pragma once
// What the renderer hands the cache with a colour it stores: the ray whose
// tree computed it and where that tree reached (cache/RayTreeBounds.h), so
// that a change of the scene drops exactly the texels it can have altered.
#include "cache/RayTreeBounds.h"
#include "core/Vec3.h"

namespace raycache {

struct RayTreeRecord {
    RayTreeBounds bounds;
    Vec3 origin, direction;   // the ray leaving the caching object
    int depth = 0;            // rays on its path, itself included (Whitted's depth rule)
    float pathWeight = 1.0f;  // product of its weights' largest channels up to and including it (minimum-weight rule)
};

}  // namespace raycache
