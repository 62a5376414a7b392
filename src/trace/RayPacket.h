#pragma once
// Sixteen rays and their hits in structure-of-arrays form, laid out as
// Embree's RTCRayHit16 (TraceScene.cpp checks every offset), so the tile
// kernel's lanes (core/FloatLanes.h) write rays straight into the packet the
// tracer traces and read its hits where the tracer left them. Code outside
// src/trace/ sees this header only, never Embree's.
#include <cstdint>

#include "core/Ray.h"

namespace raycache {

struct RayLanes16 {
    alignas(64) float originX[16], originY[16], originZ[16], tNear[16];
    float directionX[16], directionY[16], directionZ[16], time[16];
    float tFar[16];
    std::uint32_t mask[16], id[16], flags[16];
};

struct HitLanes16 {
    alignas(64) float normalX[16], normalY[16], normalZ[16];  // unnormalized geometric normal (unused here)
    float u[16], v[16];                                       // barycentrics, as TraceHit's
    std::uint32_t primitiveId[16], geometryId[16], instanceId[16];
};

struct RayHitLanes16 {
    RayLanes16 ray;
    HitLanes16 hit;
};

// Which lanes of a packet are traced: -1 traced, 0 not (Embree's valid mask).
struct PacketLanes {
    alignas(64) int valid[16];
};

// Lane k of a packet: `ray`, traced at time 0 against every geometry mask.
inline void setLaneRay(RayLanes16& rays, int k, const Ray& ray) {
    rays.originX[k] = ray.origin.x, rays.originY[k] = ray.origin.y, rays.originZ[k] = ray.origin.z;
    rays.directionX[k] = ray.direction.x, rays.directionY[k] = ray.direction.y;
    rays.directionZ[k] = ray.direction.z;
    rays.tNear[k] = ray.tNear;
    rays.tFar[k] = ray.tFar;
    rays.time[k] = 0.0f;
    rays.mask[k] = 0xFFFFFFFFu;
    rays.id[k] = 0;
    rays.flags[k] = 0;
}

// Lane k's origin and direction as one Ray (its tNear and tFar Ray's defaults).
inline Ray laneRay(const RayLanes16& rays, int k) {
    return Ray{{rays.originX[k], rays.originY[k], rays.originZ[k]},
               {rays.directionX[k], rays.directionY[k], rays.directionZ[k]}};
}

}  // namespace raycache
