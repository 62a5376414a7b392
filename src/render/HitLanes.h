#pragma once
// The tile kernel's per-hit arithmetic sixteen hits at a time
// (core/FloatLanes.h), over the wave's structure-of-arrays lanes: surfaces,
// shadow rays, direct light, albedo and secondary rays. Each lane's result
// is bit for bit what the scalar rule gives (render/SurfacePoint.h,
// tests/render/ScalarShadingRule.h): the same IEEE operations in the same order, on every
// target (AVX-512, AVX2, baseline x86-64; tests/render/HitLanesTest.cpp).
#include <cstddef>
#include <cstdint>
#include <span>

#include "render/LocalShading.h"
#include "render/MeshShading.h"
#include "render/SurfacePoint.h"
#include "scene/Material.h"
#include "trace/RayPacket.h"

namespace raycache {

// Up to sixteen triangle-mesh hits, one per lane (their rays are the
// packet's): the hit's barycentrics, the triangle's unit geometric normal,
// and its vertex normals and texture coordinates where the mesh has them.
struct MeshHitLanes {
    alignas(64) float u[16], v[16];
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

// Lane k's triangle and barycentrics for a hit on `primitiveId`: from the
// mesh's shading records when they are made for this mesh (`records` not
// null), else (a kernel not told of a move) from the mesh itself.
inline void setMeshHitLane(MeshHitLanes& lanes, std::size_t k, const TriangleMesh& mesh,
                           const MeshShadingRecords* records, int primitiveId, float u, float v) {
    const auto triangle = static_cast<std::size_t>(primitiveId);
    lanes.u[k] = u;
    lanes.v[k] = v;
    if (records) {
        setMeshTriangleLane(lanes, k, records->triangles[triangle], records->hasNormals,
                            records->hasUvs ? &records->uvs[triangle] : nullptr);
        return;
    }
    const TriangleUvRecord uv = uvRecordOf(mesh, triangle);
    setMeshTriangleLane(lanes, k, shadingRecordOf(mesh, triangle), !mesh.normals.empty(),
                        mesh.uvs.empty() ? nullptr : &uv);
}

// Every function writes only the lanes its `lanes` mask selects (-1
// selected, 0 not).

// Sixteen surface points and what their materials are there: albedos and,
// for metallic-roughness materials, metallic and roughness (the factors,
// or a texture's values: render/SurfaceTextures.h).
struct SurfaceLanes16 {
    alignas(64) float positionX[16], positionY[16], positionZ[16];
    alignas(64) float normalX[16], normalY[16], normalZ[16];
    alignas(64) float geometricX[16], geometricY[16], geometricZ[16];
    alignas(64) float u[16], v[16];
    alignas(64) float albedoR[16], albedoG[16], albedoB[16];
    alignas(64) float metallic[16], roughness[16];  // metallic-roughness materials only
    alignas(64) int frontFace[16];  // 1: the ray arrived from outside
};

// Lane k of `s` as one surface point (its albedo aside): what the kernel's
// per-hit steps read, and what the tests compare with surfacePointAt.
inline SurfacePoint laneSurface(const SurfaceLanes16& s, int k) {
    SurfacePoint sp;
    sp.position = {s.positionX[k], s.positionY[k], s.positionZ[k]};
    sp.normal = {s.normalX[k], s.normalY[k], s.normalZ[k]};
    sp.geometricNormal = {s.geometricX[k], s.geometricY[k], s.geometricZ[k]};
    sp.u = s.u[k];
    sp.v = s.v[k];
    sp.frontFace = s.frontFace[k] != 0;
    return sp;
}

// One light as sixteen surfaces see it: the direction toward it, the spot
// factor, whether a shadow ray was traced toward it (0: the light faces
// away) and whether it came back clear (1) or was blocked or never traced (0).
struct LightLanes16 {
    alignas(64) float toX[16], toY[16], toZ[16], strength[16];
    alignas(64) int traced[16], lit[16];
};

// surfacePointAt (needUv false: texture coordinates 0) for hits of `rays`
// (at their tFar) on one sphere.
void sphereSurfaceLanes16(const RayLanes16& rays, const Sphere& sphere, const int* lanes, SurfaceLanes16& out);
// surfacePointAt (needUv true) for hits of `rays` (at their tFar) on the
// triangles of `triangles`.
void meshSurfaceLanes16(const RayLanes16& rays, const MeshHitLanes& triangles, const int* lanes,
                        SurfaceLanes16& out);

// Light `light`'s shadow rays from the surfaces' lanes, as
// LocalShading::shadowQueries makes them: `rays` gets them and `traced` the
// lanes that need one (selected, and the light reaches the surface). Fills
// `seen`'s directions and strengths; its `traced` and `lit` are the
// caller's to set once the rays are traced.
void shadowRayLanes16(const Light& light, const SpotCone& spot, const SurfaceLanes16& surfaces, const int* lanes,
                      RayLanes16& rays, PacketLanes& traced, LightLanes16& seen);

// The scalar shading rule (tests/render/ScalarShadingRule.h) for the
// selected lanes, all of one material, seen along `viewRays`' directions: out{R,G,B}[k] for each selected k.
void directLightLanes16(const Material& material, std::span<const Light> lights, const LightLanes16* seen,
                        const SurfaceLanes16& surfaces, const RayLanes16& viewRays, const int* lanes, float* outR,
                        float* outG, float* outB);

// The scalar rule's view-independent part (scalarViewIndependentLight) for
// the selected lanes, all of one material (each lane's metallic from `surfaces`), with the surfaces' albedo
// or, `whiteAlbedo`, an albedo of 1: out{R,G,B}[k] for each selected k. The
// lights counted are those whose `lit` lane is set (the lit mask is the
// caller's to take from them).
void viewIndependentLightLanes16(const Material& material, std::span<const Light> lights, const LightLanes16* seen,
                                 const SurfaceLanes16& surfaces, bool whiteAlbedo, const int* lanes, float* outR,
                                 float* outG, float* outB);

// The scalar rule's highlights (scalarHighlights) for the selected lanes,
// all of one material (each lane's metallic and roughness from `surfaces`), seen along `viewRays`'
// directions, from the lights whose `lit` lane is set: out{R,G,B}[k].
void highlightLanes16(const Material& material, std::span<const Light> lights, const LightLanes16* seen,
                      const SurfaceLanes16& surfaces, const RayLanes16& viewRays, const int* lanes, float* outR,
                      float* outG, float* outB);

// The albedo of `pattern` (Texture::sample's checkerboard) at the texture
// coordinates of the surfaces k selected by `lanes`, into their albedo lanes.
void checkerAlbedoLanes16(const Checkerboard& pattern, const int* lanes, SurfaceLanes16& surfaces);

// The secondary rays of sixteen hits of one material: the reflected and
// refracted rays and their weights per channel (secondaryRayWeights,
// tests/render/SecondaryRayWeights.h: Whitted's constants, or Fresnel's for
// metallic-roughness materials).
struct SecondaryRayLanes16 {
    alignas(64) float reflectedX[16], reflectedY[16], reflectedZ[16];  // unit directions
    alignas(64) float aboveX[16], aboveY[16], aboveZ[16];              // their origins, lifted off the surface
    alignas(64) float refractedX[16], refractedY[16], refractedZ[16];
    alignas(64) float belowX[16], belowY[16], belowZ[16];              // the refracted rays' origins
    alignas(64) float reflectR[16], reflectG[16], reflectB[16];  // the reflected ray's weight
    alignas(64) float refractR[16], refractG[16], refractB[16];  // the refracted ray's weight
    alignas(64) float coneWidth[16], coneSpread[16];
    alignas(64) int reflects[16], refracts[16];  // 1: the ray is spawned
    // The CCT texel each ray addresses on its object's cube, where the tile
    // kernel addressed it (RayCache::laneAddressedFaceSize); -1 elsewhere.
    alignas(64) int reflectedTexel[16], refractedTexel[16];
    // kAskedAtEmit where the tile kernel looks the ray up itself when it
    // emits it (RayCache::looksUpInLanes, lookupAddressed); -1 where the
    // lookup batch asks, or no cache does.
    static constexpr int kAskedAtEmit = 2;
    alignas(64) int reflectedAnswered[16], refractedAnswered[16];
    bool any = false;  // whether any lane spawns a ray
};

// The rays surfaces k (selected by `lanes`) of `material` spawn, hit by
// `rays` at their tFar, whose paths weigh pathWeight[k] and whose cones are
// {coneWidth[k], coneSpread[k]}: `curvature` as coneCurvature gives it,
// `minWeight` RenderSettings::minWeight (render/RayCone.h). A ray is
// spawned where its path weight times its weight's largest channel is at
// least minWeight (and that channel is above 0).
void secondaryRayLanes16(const Material& material, float curvature, float minWeight, const SurfaceLanes16& surfaces,
                         const RayLanes16& rays, const float* pathWeight, const float* coneWidth,
                         const float* coneSpread, const int* lanes, SecondaryRayLanes16& out);

}  // namespace raycache
