#pragma once
#include "core/Vec3.h"

namespace raycache {

// Nearest hit along a ray, as reported by the tracer. objectId indexes
// Scene::objects; -1 means the ray hit nothing.
struct TraceHit {
    float t = 0.0f;
    int objectId = -1;
    int primitiveId = -1;  // triangle index within a mesh; 0 for spheres
    float u = 0.0f;        // barycentrics: p = (1-u-v) v0 + u v1 + v v2
    float v = 0.0f;

    bool hit() const { return objectId >= 0; }
};

}  // namespace raycache
