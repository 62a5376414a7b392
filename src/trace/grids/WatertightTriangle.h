#pragma once
// Watertight ray/triangle intersection (Woop, Benthin, Wald, "Watertight
// Ray/Triangle Intersection", JCGT 2013): the ray is sheared so it points
// along +z, and the three edge functions are evaluated in 2D in a way that
// gives a point on an edge shared by two triangles to at least one of them,
// whatever the rounding. Edge values that round to exactly zero are
// recomputed in double, as the paper prescribes.
#include <cmath>
#include <utility>

#include "core/Ray.h"
#include "core/Vec3.h"

namespace raycache {

// The per-ray part of the test: which axis the ray is sheared along, the
// shear, and the segment. Computed once per ray, used for every triangle.
struct WatertightRay {
    Vec3 origin;
    int kx = 0, ky = 1, kz = 2;
    float sx = 0.0f, sy = 0.0f, sz = 1.0f;
    float tNear = 0.0f, tFar = 0.0f;

    // The axes alone, without the shear's divisions: kz the direction's
    // major axis, (kx, ky) the others in the order that keeps the edge
    // functions' winding when the major axis points backwards.
    static void shearAxes(const Vec3& d, int& kx, int& ky, int& kz) {
        const float ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
        kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
        kx = kz == 2 ? 0 : kz + 1;
        ky = kx == 2 ? 0 : kx + 1;
        if (d[kz] < 0.0f) std::swap(kx, ky);
    }

    explicit WatertightRay(const Ray& ray) : origin(ray.origin), tNear(ray.tNear), tFar(ray.tFar) {
        const Vec3& d = ray.direction;
        shearAxes(d, kx, ky, kz);
        sx = d[kx] / d[kz];
        sy = d[ky] / d[kz];
        sz = 1.0f / d[kz];
    }
};

// A hit at distance t with barycentrics u, v (p = (1-u-v) v0 + u v1 + v v2).
struct TriangleHit {
    float t, u, v;
};

// True when the ray meets the triangle at tNear < t <= tFar (both sides;
// degenerate triangles never hit). `hit` is written only on success.
inline bool intersectWatertight(const WatertightRay& r, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                                TriangleHit& hit) {
    const Vec3 a = p0 - r.origin, b = p1 - r.origin, c = p2 - r.origin;
    const float ax = a[r.kx] - r.sx * a[r.kz], ay = a[r.ky] - r.sy * a[r.kz];
    const float bx = b[r.kx] - r.sx * b[r.kz], by = b[r.ky] - r.sy * b[r.kz];
    const float cx = c[r.kx] - r.sx * c[r.kz], cy = c[r.ky] - r.sy * c[r.kz];
    float u = cx * by - cy * bx;
    float v = ax * cy - ay * cx;
    float w = bx * ay - by * ax;
    if (u == 0.0f || v == 0.0f || w == 0.0f) {
        u = static_cast<float>(static_cast<double>(cx) * by - static_cast<double>(cy) * bx);
        v = static_cast<float>(static_cast<double>(ax) * cy - static_cast<double>(ay) * cx);
        w = static_cast<float>(static_cast<double>(bx) * ay - static_cast<double>(by) * ax);
    }
    if ((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f)) return false;
    const float det = u + v + w;
    if (det == 0.0f) return false;
    const float az = r.sz * a[r.kz], bz = r.sz * b[r.kz], cz = r.sz * c[r.kz];
    const float t = u * az + v * bz + w * cz;
    // t / det must lie in (tNear, tFar]: compared without dividing, sign of det folded in.
    const float absDet = std::fabs(det);
    const float signedT = det < 0.0f ? -t : t;
    if (!(signedT > r.tNear * absDet) || !(signedT <= r.tFar * absDet)) return false;
    const float inverseDet = 1.0f / det;
    hit = {t * inverseDet, v * inverseDet, w * inverseDet};
    return true;
}

// The test's float path without a branch, for one lane of a packet (the
// grids vectorise loops over it, trace/grids/FrustumGridTraversal.cpp): the corners
// a, b, c relative to the lane's origin, already in its (kx, ky, kz) order,
// and the lane's shear and segment. The same operations as
// intersectWatertight, so a lane's answer is bit for bit the ray's, except
// where `zeroEdge` is set: an edge value rounded to exactly zero, which
// intersectWatertight redoes in double.
struct WatertightLane {
    float v, w, det, t;  // the hit is at t / det, barycentrics v / det, w / det
    bool accepted, zeroEdge;
};

[[gnu::always_inline]] inline WatertightLane watertightLane(float akx, float aky, float akz, float bkx, float bky,
                                                            float bkz, float ckx, float cky, float ckz, float sx,
                                                            float sy, float sz, float tNear, float tFar) {
    const float ax = akx - sx * akz, ay = aky - sy * akz;
    const float bx = bkx - sx * bkz, by = bky - sy * bkz;
    const float cx = ckx - sx * ckz, cy = cky - sy * ckz;
    const float u = cx * by - cy * bx;
    const float v = ax * cy - ay * cx;
    const float w = bx * ay - by * ax;
    const float det = u + v + w;
    const float t = u * (sz * akz) + v * (sz * bkz) + w * (sz * ckz);
    const float absDet = std::fabs(det);
    const float signedT = det < 0.0f ? -t : t;
    // Bitwise, not short-circuit, so a loop over lanes has no branches to stop vectorisation.
    const bool negative = (u < 0.0f) | (v < 0.0f) | (w < 0.0f);
    const bool positive = (u > 0.0f) | (v > 0.0f) | (w > 0.0f);
    const bool zeroEdge = (u == 0.0f) | (v == 0.0f) | (w == 0.0f);
    const bool accepted = !(negative & positive) & (det != 0.0f) & (signedT > tNear * absDet) &
                          (signedT <= tFar * absDet);
    return {v, w, det, t, accepted, zeroEdge};
}

}  // namespace raycache
