#pragma once
// Geometry at a ray hit, oriented toward the side the ray came from: the one
// rule every first stage and bounce of the tile kernel uses, whether the hit
// comes from the tracer or from a G-buffer.
#include "core/Ray.h"
#include "raster/GBuffer.h"
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

// The diffuse albedo at a hit, as surfacePointAt's texture coordinates
// give it, without the rest of the surface (normals, orientation): one
// texture fetch where the Render Cache moves a sample's shading to its
// pixel's centre (rendercache/SampleRetexturing.h).
Rgb albedoAtHit(const SceneObject& object, const Ray& ray, const TraceHit& hit);

// The surface the tracer's hit would give, from G-buffer pixel i (which must
// hold a surface): position and shading normal from the G-buffer, the
// triangle's geometric normal, both turned toward the camera ray as above.
// Texture coordinates are not rebuilt (the G-buffer carries the albedo).
SurfacePoint surfacePointFromGBuffer(const Scene& scene, const GBufferView& gbuffer, std::size_t i,
                                     const Vec3& rayDirection);

}  // namespace raycache
