#include "render/HitLanes.h"

#include "core/FloatLanes.h"
#include "core/LaneClones.h"

#include <limits>

namespace raycache {

namespace {

// Lane k of `mask` as a bool.
[[gnu::always_inline]] inline bool laneSet(const FloatMask& mask, int k) { return mask[k] != 0; }

// The rays' directions and their hit points origin + direction * t
// (surfacePointAt's position), from sphere or mesh hit lanes.
template <class HitLanes>
[[gnu::always_inline]] inline void hitPointLanes(const HitLanes& h, FloatLanes& dx, FloatLanes& dy, FloatLanes& dz,
                                                 FloatLanes& px, FloatLanes& py, FloatLanes& pz) {
    FloatLanes ox, oy, oz, t;
    loadLanes(h.originX, ox);
    loadLanes(h.originY, oy);
    loadLanes(h.originZ, oz);
    loadLanes(h.directionX, dx);
    loadLanes(h.directionY, dy);
    loadLanes(h.directionZ, dz);
    loadLanes(h.t, t);
    px = ox + dx * t, py = oy + dy * t, pz = oz + dz * t;
}

// a * w + b * u + c * v lane by lane, from three arrays of sixteen: a
// triangle's vertex attribute at barycentrics (u, v), in meshSurface's order.
[[gnu::always_inline]] inline void interpolateLanes(const float* a, const float* b, const float* c,
                                                    const FloatLanes& w, const FloatLanes& u, const FloatLanes& v,
                                                    FloatLanes& out) {
    FloatLanes la, lb, lc;
    loadLanes(a, la);
    loadLanes(b, lb);
    loadLanes(c, lc);
    out = la * w + lb * u + lc * v;
}

// GCC resolves a function's clones in the file that defines them: the
// exported functions below call these.
RAYCACHE_WIDE_LANE_CLONES
void sphereSurfaceLanes(const SphereHitLanes& hits, int count, SurfacePoint* out) {
    FloatLanes dx, dy, dz, px, py, pz, cx, cy, cz, radius;
    hitPointLanes(hits, dx, dy, dz, px, py, pz);
    loadLanes(hits.centerX, cx);
    loadLanes(hits.centerY, cy);
    loadLanes(hits.centerZ, cz);
    loadLanes(hits.radius, radius);
    // surfacePointAt's steps: normal = (position - centre) * (1 / radius);
    // turned toward the ray.
    const FloatLanes inverseRadius = 1.0f / radius;
    FloatLanes nx = (px - cx) * inverseRadius, ny = (py - cy) * inverseRadius, nz = (pz - cz) * inverseRadius;
    const FloatMask front = dx * nx + dy * ny + dz * nz < 0.0f;
    nx = front ? nx : -nx;
    ny = front ? ny : -ny;
    nz = front ? nz : -nz;
    for (int k = 0; k < count; ++k) {
        SurfacePoint& sp = out[k];
        sp.position = {px[k], py[k], pz[k]};
        sp.normal = sp.geometricNormal = {nx[k], ny[k], nz[k]};
        sp.u = sp.v = 0.0f;
        sp.frontFace = laneSet(front, k);
    }
}

// Lanes that are set where the ints are non-zero.
[[gnu::always_inline]] inline void maskOf(const int* flags, FloatMask& mask) {
    for (int k = 0; k < kFloatLanes; ++k) mask[k] = flags[k] != 0 ? -1 : 0;
}

RAYCACHE_WIDE_LANE_CLONES
void meshSurfaceLanes(const MeshHitLanes& h, int count, SurfacePoint* out) {
    FloatLanes dx, dy, dz, px, py, pz, u, v;
    hitPointLanes(h, dx, dy, dz, px, py, pz);
    loadLanes(h.u, u);
    loadLanes(h.v, v);
    const FloatLanes w = 1.0f - u - v;
    // The interpolated vertex normal, unit where it has a length (meshSurface).
    FloatMask hasShadingNormal;
    maskOf(h.hasNormals, hasShadingNormal);
    FloatLanes sx, sy, sz;
    interpolateLanes(h.normal0X, h.normal1X, h.normal2X, w, u, v, sx);
    interpolateLanes(h.normal0Y, h.normal1Y, h.normal2Y, w, u, v, sy);
    interpolateLanes(h.normal0Z, h.normal1Z, h.normal2Z, w, u, v, sz);
    FloatLanes length;
    sqrtLanes(sx * sx + sy * sy + sz * sz, length);
    hasShadingNormal &= length > 0.0f;
    const FloatLanes inverseLength = 1.0f / length;
    sx = sx * inverseLength, sy = sy * inverseLength, sz = sz * inverseLength;
    // The geometric normal (unitTriangleNormal, made once per pose), on the
    // shading normal's side (triangleNormal).
    FloatLanes gx, gy, gz;
    loadLanes(h.geometricX, gx);
    loadLanes(h.geometricY, gy);
    loadLanes(h.geometricZ, gz);
    const FloatMask flip = hasShadingNormal & (gx * sx + gy * sy + gz * sz < 0.0f);
    gx = flip ? -gx : gx;
    gy = flip ? -gy : gy;
    gz = flip ? -gz : gz;
    FloatLanes nx = hasShadingNormal ? sx : gx, ny = hasShadingNormal ? sy : gy, nz = hasShadingNormal ? sz : gz;
    // Texture coordinates, where the mesh has them.
    FloatLanes tu, tv;
    interpolateLanes(h.uv0U, h.uv1U, h.uv2U, w, u, v, tu);
    interpolateLanes(h.uv0V, h.uv1V, h.uv2V, w, u, v, tv);
    FloatMask hasUvs;
    maskOf(h.hasUvs, hasUvs);
    tu = hasUvs ? tu : FloatLanes{};
    tv = hasUvs ? tv : FloatLanes{};
    // Turned toward the ray (faceToward).
    const FloatMask front = dx * gx + dy * gy + dz * gz < 0.0f;
    nx = front ? nx : -nx, ny = front ? ny : -ny, nz = front ? nz : -nz;
    gx = front ? gx : -gx, gy = front ? gy : -gy, gz = front ? gz : -gz;
    for (int k = 0; k < count; ++k) {
        SurfacePoint& sp = out[k];
        sp.position = {px[k], py[k], pz[k]};
        sp.normal = {nx[k], ny[k], nz[k]};
        sp.geometricNormal = {gx[k], gy[k], gz[k]};
        sp.u = tu[k];
        sp.v = tv[k];
        sp.frontFace = laneSet(front, k);
    }
}

// surfaceOffset (render/LocalShading.h): 1e-4 * max(|x|, |y|, |z|, 1), in
// std::max's order of comparisons.
[[gnu::always_inline]] inline void surfaceOffsetLanes(const FloatLanes& px, const FloatLanes& py,
                                                      const FloatLanes& pz, FloatLanes& offset) {
    FloatLanes ax, ay, az;
    absLanes(px, ax);
    absLanes(py, ay);
    absLanes(pz, az);
    FloatLanes extent = ax;
    extent = extent < ay ? ay : extent;
    extent = extent < az ? az : extent;
    extent = extent < 1.0f ? FloatLanes{} + 1.0f : extent;
    offset = 1e-4f * extent;
}

// smoothstep(edge0, edge1, x) of LocalShading, lane by lane.
[[gnu::always_inline]] inline void smoothstepLanes(float edge0, float edge1, const FloatLanes& x, FloatLanes& out) {
    if (edge1 <= edge0) {
        out = x >= edge1 ? FloatLanes{} + 1.0f : FloatLanes{};
        return;
    }
    FloatLanes t = (x - edge0) / (edge1 - edge0);
    t = t < 0.0f ? FloatLanes{} : t;  // std::clamp(t, 0, 1): t < lo ? lo : (hi < t ? hi : t)
    t = 1.0f < t ? FloatLanes{} + 1.0f : t;
    out = t * t * (3.0f - 2.0f * t);
}

RAYCACHE_WIDE_LANE_CLONES
int shadowQueryLanes(std::span<const Light> lights, std::span<const SpotCone> spot, const SurfacePoint* surfaces,
                     int count, ShadowQuery* out, int* firstQuery) {
    FloatLanes px{}, py{}, pz{}, nx{}, ny{}, nz{}, gx{}, gy{}, gz{};
    for (int k = 0; k < count; ++k) {
        const SurfacePoint& sp = surfaces[k];
        px[k] = sp.position.x, py[k] = sp.position.y, pz[k] = sp.position.z;
        nx[k] = sp.normal.x, ny[k] = sp.normal.y, nz[k] = sp.normal.z;
        gx[k] = sp.geometricNormal.x, gy[k] = sp.geometricNormal.y, gz[k] = sp.geometricNormal.z;
    }
    FloatLanes offset;
    surfaceOffsetLanes(px, py, pz, offset);
    const FloatLanes qx = px + gx * offset, qy = py + gy * offset, qz = pz + gz * offset;
    // Per light: the direction, distance and strength, and which lanes it reaches.
    constexpr int kLights = static_cast<int>(kMaxLights);
    FloatLanes toX[kLights], toY[kLights], toZ[kLights], distance[kLights], strength[kLights];
    FloatMask reaches[kLights];
    const int lightCount = static_cast<int>(lights.size());
    for (int l = 0; l < lightCount; ++l) {
        const Light& light = lights[static_cast<std::size_t>(l)];
        strength[l] = FloatLanes{} + 1.0f;
        if (light.type == LightType::Directional) {
            toX[l] = -(FloatLanes{} + light.direction.x);  // negated, not 0 - x: a zero keeps its sign flipped
            toY[l] = -(FloatLanes{} + light.direction.y);
            toZ[l] = -(FloatLanes{} + light.direction.z);
            distance[l] = FloatLanes{} + std::numeric_limits<float>::infinity();
        } else {
            const FloatLanes ddx = light.position.x - px, ddy = light.position.y - py, ddz = light.position.z - pz;
            const FloatLanes squared = ddx * ddx + ddy * ddy + ddz * ddz;
            FloatLanes root;
            sqrtLanes(squared, root);
            const FloatLanes inverseDistance = 1.0f / root;
            distance[l] = squared * inverseDistance;
            toX[l] = ddx * inverseDistance;
            toY[l] = ddy * inverseDistance;
            toZ[l] = ddz * inverseDistance;
            if (light.type == LightType::Spot) {
                // dot(-toLight, light.direction)
                const FloatLanes cosine =
                    -toX[l] * light.direction.x + -toY[l] * light.direction.y + -toZ[l] * light.direction.z;
                smoothstepLanes(spot[static_cast<std::size_t>(l)].outer, spot[static_cast<std::size_t>(l)].inner,
                                cosine, strength[l]);
            }
        }
        // Lights below the geometric surface would leak through interpolated normals.
        const FloatLanes shadingCosine = nx * toX[l] + ny * toY[l] + nz * toZ[l];
        const FloatLanes geometricCosine = gx * toX[l] + gy * toY[l] + gz * toZ[l];
        // Written as the scalar test's negation, so NaN lanes go the same way.
        reaches[l] = ~((strength[l] <= 0.0f) | (shadingCosine <= 0.0f) | (geometricCosine <= 0.0f));
    }
    int written = 0;
    for (int k = 0; k < count; ++k) {
        firstQuery[k] = written;
        const Vec3 origin{qx[k], qy[k], qz[k]};
        for (int l = 0; l < lightCount; ++l)
            if (laneSet(reaches[l], k))
                out[written++] = ShadowQuery{Ray{origin, {toX[l][k], toY[l][k], toZ[l][k]}, 0.0f, distance[l][k]}, l,
                                             strength[l][k]};
    }
    firstQuery[count] = written;
    return written;
}

}  // namespace

void meshSurfaces16(const MeshHitLanes& hits, int count, SurfacePoint* out) { meshSurfaceLanes(hits, count, out); }

void sphereSurfaces16(const SphereHitLanes& hits, int count, SurfacePoint* out) {
    sphereSurfaceLanes(hits, count, out);
}

int shadowQueries16(std::span<const Light> lights, std::span<const SpotCone> spot, const SurfacePoint* surfaces,
                    int count, ShadowQuery* out, int* firstQuery) {
    return shadowQueryLanes(lights, spot, surfaces, count, out, firstQuery);
}

}  // namespace raycache
