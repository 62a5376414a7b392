#pragma once
// The one ray-sphere root of the tracer, shared by the Embree backend (user
// geometry) and the grids (trace/grids/), so both accelerators give a sphere
// hit the same distance bit for bit.
#include <cmath>
#include <utility>

#include "scene/SceneObject.h"

namespace raycache {

// Nearest root of |o + t d - c| = r inside [tnear, tfar], or a negative value.
// Solved relative to the centre with the numerically stable quadratic form.
inline float sphereRoot(const Sphere& s, float ox, float oy, float oz, float dx, float dy, float dz, float tnear,
                        float tfar) {
    const float px = ox - s.center.x, py = oy - s.center.y, pz = oz - s.center.z;
    const float a = dx * dx + dy * dy + dz * dz;
    const float b = px * dx + py * dy + pz * dz;
    // c computed as |p - (p.d/a) d|^2 - r^2 loses less precision far from the sphere.
    const float k = b / a;
    const float qx = px - k * dx, qy = py - k * dy, qz = pz - k * dz;
    const float disc = s.radius * s.radius - (qx * qx + qy * qy + qz * qz);
    if (disc < 0.0f) return -1.0f;
    const float h = std::sqrt(a * disc);
    const float q = b > 0.0f ? -(b + h) : -(b - h);
    float t0 = (b > 0.0f ? q / a : ((px * px + py * py + pz * pz) - s.radius * s.radius) / q);
    float t1 = (b > 0.0f ? ((px * px + py * py + pz * pz) - s.radius * s.radius) / q : q / a);
    if (t0 > t1) std::swap(t0, t1);
    if (t0 >= tnear && t0 <= tfar) return t0;
    if (t1 >= tnear && t1 <= tfar) return t1;
    return -1.0f;
}

}  // namespace raycache
