#pragma once
// The tile kernel's per-hit arithmetic sixteen hits at a time
// (core/FloatLanes.h): the surface at a sphere hit, and the shadow queries
// of a batch of surfaces. Each lane's result is bit for bit what the scalar
// code gives (render/SurfacePoint.h, LocalShading::shadowQueries): the same
// IEEE operations in the same order, on every target (AVX-512, AVX2,
// baseline x86-64; tests/render/HitLanesTest.cpp). The kernel keeps its
// records in arrays of structures; the lanes gather from and scatter to them.
#include <cstddef>
#include <cstdint>
#include <span>

#include "render/LocalShading.h"
#include "render/MeshShading.h"
#include "render/SurfacePoint.h"

namespace raycache {

// Up to sixteen sphere hits, one per lane: the ray, its distance, the sphere.
struct SphereHitLanes {
    alignas(64) float originX[16], originY[16], originZ[16];
    alignas(64) float directionX[16], directionY[16], directionZ[16];
    alignas(64) float t[16];
    alignas(64) float centerX[16], centerY[16], centerZ[16], radius[16];
};

// out[k] = surfacePointAt(sphere k, ray k, hit at t k, needUv = false) for
// k < count (texture coordinates 0).
void sphereSurfaces16(const SphereHitLanes& hits, int count, SurfacePoint* out);

// Up to sixteen triangle-mesh hits, one per lane: the ray, the hit's
// distance and barycentrics, the triangle's unit geometric normal, and its
// vertex normals and texture coordinates where the mesh has them.
struct MeshHitLanes {
    alignas(64) float originX[16], originY[16], originZ[16];
    alignas(64) float directionX[16], directionY[16], directionZ[16];
    alignas(64) float t[16], u[16], v[16];
    alignas(64) float geometricX[16], geometricY[16], geometricZ[16];
    alignas(64) float normal0X[16], normal0Y[16], normal0Z[16];
    alignas(64) float normal1X[16], normal1Y[16], normal1Z[16];
    alignas(64) float normal2X[16], normal2Y[16], normal2Z[16];
    alignas(64) float uv0U[16], uv0V[16], uv1U[16], uv1V[16], uv2U[16], uv2V[16];
    alignas(64) int hasNormals[16], hasUvs[16];  // non-zero: the mesh has them (else those lanes are ignored)
};

// Lane k's triangle from its records (render/MeshShading.h); `uv` null when
// the mesh has no texture coordinates.
inline void setMeshTriangleLane(MeshHitLanes& lanes, std::size_t k, const TriangleShadingRecord& triangle,
                                bool hasNormals, const TriangleUvRecord* uv) {
    lanes.geometricX[k] = triangle.geometricNormal.x;
    lanes.geometricY[k] = triangle.geometricNormal.y;
    lanes.geometricZ[k] = triangle.geometricNormal.z;
    lanes.hasNormals[k] = hasNormals ? 1 : 0;
    lanes.normal0X[k] = triangle.normal0.x, lanes.normal0Y[k] = triangle.normal0.y, lanes.normal0Z[k] = triangle.normal0.z;
    lanes.normal1X[k] = triangle.normal1.x, lanes.normal1Y[k] = triangle.normal1.y, lanes.normal1Z[k] = triangle.normal1.z;
    lanes.normal2X[k] = triangle.normal2.x, lanes.normal2Y[k] = triangle.normal2.y, lanes.normal2Z[k] = triangle.normal2.z;
    lanes.hasUvs[k] = uv ? 1 : 0;
    const TriangleUvRecord none{};
    const TriangleUvRecord& t = uv ? *uv : none;
    lanes.uv0U[k] = t.uv0[0], lanes.uv0V[k] = t.uv0[1];
    lanes.uv1U[k] = t.uv1[0], lanes.uv1V[k] = t.uv1[1];
    lanes.uv2U[k] = t.uv2[0], lanes.uv2V[k] = t.uv2[1];
}

// out[k] = surfacePointAt(the mesh, ray k, hit k, needUv = true) for k < count.
void meshSurfaces16(const MeshHitLanes& hits, int count, SurfacePoint* out);

// The shadow queries of surfaces[0..count) (count <= 16) as
// LocalShading::shadowQueries writes them, surface after surface: the
// queries of surface k go to out from firstQuery[k] on, firstQuery[k + 1]
// past them. `spot` holds each light's cone (used for spot lights). Returns the number of queries written.
int shadowQueries16(std::span<const Light> lights, std::span<const SpotCone> spot, const SurfacePoint* surfaces,
                    int count, ShadowQuery* out, int* firstQuery);

}  // namespace raycache
