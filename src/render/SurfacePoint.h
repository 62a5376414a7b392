#pragma once
// Geometry at a ray hit, oriented toward the side the ray came from.
#include "core/Ray.h"
#include "scene/Scene.h"
#include "trace/TraceHit.h"

namespace raycache {

struct SurfacePoint {
    Vec3 position;
    Vec3 normal;            // shading normal, unit, on the incoming ray's side
    Vec3 geometricNormal;   // unit, on the incoming ray's side
    float u = 0.0f, v = 0.0f;  // texture coordinates
    bool frontFace = true;  // the ray arrived from outside the object
};

// Texture coordinates cost trigonometry on spheres, so they are computed only
// when `needUv` is set (the material has a texture); otherwise they stay 0.
SurfacePoint surfacePointAt(const SceneObject& object, const Ray& ray, const TraceHit& hit, bool needUv);

}  // namespace raycache
