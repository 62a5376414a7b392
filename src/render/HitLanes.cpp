#include "render/HitLanes.h"

#include <limits>

#include "core/FloatLanes.h"
#include "core/LaneLevels.h"
#include "render/MetallicRoughness.h"
#include "render/SpecularPower.h"

namespace raycache {

#define RAYCACHE_LANE_KERNELS "render/HitLaneKernels.inc"
#include "core/LaneLevelsInclude.h"

void sphereSurfaceLanes16(const RayLanes16& rays, const Sphere& sphere, const int* lanes, SurfaceLanes16& out) {
    RAYCACHE_LANE_DISPATCH(sphereSurfaceLanes, rays, sphere, lanes, out);
}

void meshSurfaceLanes16(const RayLanes16& rays, const MeshHitLanes& triangles, const int* lanes,
                        SurfaceLanes16& out) {
    RAYCACHE_LANE_DISPATCH(meshSurfaceLanes, rays, triangles, lanes, out);
}

void shadowRayLanes16(const Light& light, const SpotCone& spot, const SurfaceLanes16& surfaces, const int* lanes,
                      RayLanes16& rays, PacketLanes& traced, LightLanes16& seen) {
    RAYCACHE_LANE_DISPATCH(shadowRayLanes, light, spot, surfaces, lanes, rays, traced, seen);
}

void directLightLanes16(const Material& material, std::span<const Light> lights, const LightLanes16* seen,
                        const SurfaceLanes16& surfaces, const RayLanes16& viewRays, const int* lanes, float* outR,
                        float* outG, float* outB) {
    RAYCACHE_LANE_DISPATCH(directLightLanes, material, lights, seen, surfaces, viewRays, lanes, outR, outG, outB);
}

void viewIndependentLightLanes16(const Material& material, std::span<const Light> lights, const LightLanes16* seen,
                                 const SurfaceLanes16& surfaces, bool whiteAlbedo, const int* lanes, float* outR,
                                 float* outG, float* outB) {
    RAYCACHE_LANE_DISPATCH(viewIndependentLightLanes, material, lights, seen, surfaces, whiteAlbedo, lanes, outR, outG,
                           outB);
}

void highlightLanes16(const Material& material, std::span<const Light> lights, const LightLanes16* seen,
                      const SurfaceLanes16& surfaces, const RayLanes16& viewRays, const int* lanes, float* outR,
                      float* outG, float* outB) {
    RAYCACHE_LANE_DISPATCH(highlightLanes, material, lights, seen, surfaces, viewRays, lanes, outR, outG, outB);
}

void checkerAlbedoLanes16(const Checkerboard& pattern, const int* lanes, SurfaceLanes16& surfaces) {
    RAYCACHE_LANE_DISPATCH(checkerAlbedoLanes, pattern, lanes, surfaces);
}

void secondaryRayLanes16(const Material& material, float curvature, float minWeight, const SurfaceLanes16& surfaces,
                         const RayLanes16& rays, const float* pathWeight, const float* coneWidth,
                         const float* coneSpread, const int* lanes, SecondaryRayLanes16& out) {
    RAYCACHE_LANE_DISPATCH(secondaryRayLanes, material, curvature, minWeight, surfaces, rays, pathWeight, coneWidth,
                           coneSpread, lanes, out);
}

}  // namespace raycache
