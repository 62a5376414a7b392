#include "trace/SphereLanes.h"

#include "core/FloatLanes.h"
#include "core/LaneClones.h"

namespace raycache {

namespace {

// GCC resolves a function's clones in the file that defines them: callers
// elsewhere go through sphereRoots16 below.
RAYCACHE_WIDE_LANE_CLONES
void solveLanes(const Sphere& sphere, const RayLanePointers& rays, const int* active, float* t) {
    static_assert(kFloatLanes == 16);
    FloatLanes ox, oy, oz, dx, dy, dz, tnear, tfar;
    loadLanes(rays.originX, ox);
    loadLanes(rays.originY, oy);
    loadLanes(rays.originZ, oz);
    loadLanes(rays.directionX, dx);
    loadLanes(rays.directionY, dy);
    loadLanes(rays.directionZ, dz);
    loadLanes(rays.tNear, tnear);
    loadLanes(rays.tFar, tfar);
    // The steps of sphereRoot, in its order (its comments say why).
    const FloatLanes px = ox - sphere.center.x, py = oy - sphere.center.y, pz = oz - sphere.center.z;
    const FloatLanes a = dx * dx + dy * dy + dz * dz;
    const FloatLanes b = px * dx + py * dy + pz * dz;
    const FloatLanes k = b / a;
    const FloatLanes qx = px - k * dx, qy = py - k * dy, qz = pz - k * dz;
    const FloatLanes disc = sphere.radius * sphere.radius - (qx * qx + qy * qy + qz * qz);
    FloatLanes h;
    sqrtLanes(a * disc, h);  // NaN where disc < 0: those lanes are dropped below
    const FloatMask bPositive = b > 0.0f;
    const FloatLanes q = bPositive ? -(b + h) : -(b - h);
    const FloatLanes c = (px * px + py * py + pz * pz) - sphere.radius * sphere.radius;
    const FloatLanes qOverA = q / a, cOverQ = c / q;
    FloatLanes t0 = bPositive ? qOverA : cOverQ;
    FloatLanes t1 = bPositive ? cOverQ : qOverA;
    const FloatMask swap = t0 > t1;
    const FloatLanes near = swap ? t1 : t0, far = swap ? t0 : t1;
    t0 = near;
    t1 = far;
    FloatMask live;
    for (int lane = 0; lane < kFloatLanes; ++lane) live[lane] = active[lane] != 0 ? -1 : 0;
    const FloatMask hits = live & ~(disc < 0.0f);
    const FloatLanes none = FloatLanes{} - 1.0f;
    const FloatMask t0Inside = (t0 >= tnear) & (t0 <= tfar), t1Inside = (t1 >= tnear) & (t1 <= tfar);
    const FloatLanes root = t0Inside ? t0 : (t1Inside ? t1 : none);
    storeLanes(hits ? root : none, t);
}

}  // namespace

void sphereRoots16(const Sphere& sphere, const RayLanePointers& rays, const int* active, float* t) {
    solveLanes(sphere, rays, active, t);
}

}  // namespace raycache
