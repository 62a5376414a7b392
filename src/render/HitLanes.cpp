#include "render/HitLanes.h"

#include "core/FloatLanes.h"
#include "core/LaneClones.h"
#include "render/SpecularPower.h"

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

// The same from a tracer's packet, whose tFar holds the hit distance.
[[gnu::always_inline]] inline void hitPointLanes(const RayLanes16& h, FloatLanes& dx, FloatLanes& dy, FloatLanes& dz,
                                                 FloatLanes& px, FloatLanes& py, FloatLanes& pz) {
    FloatLanes ox, oy, oz, t;
    loadLanes(h.originX, ox);
    loadLanes(h.originY, oy);
    loadLanes(h.originZ, oz);
    loadLanes(h.directionX, dx);
    loadLanes(h.directionY, dy);
    loadLanes(h.directionZ, dz);
    loadLanes(h.tFar, t);
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
// surfacePointAt's steps at sphere hits: normal = (position - centre) *
// (1 / radius), turned toward the ray.
template <class Rays>
[[gnu::always_inline]] inline void sphereSurfaceCore(const Rays& rays, const FloatLanes& cx, const FloatLanes& cy,
                                                     const FloatLanes& cz, const FloatLanes& inverseRadius,
                                                     FloatLanes& px, FloatLanes& py, FloatLanes& pz, FloatLanes& nx,
                                                     FloatLanes& ny, FloatLanes& nz, FloatMask& front) {
    FloatLanes dx, dy, dz;
    hitPointLanes(rays, dx, dy, dz, px, py, pz);
    nx = (px - cx) * inverseRadius, ny = (py - cy) * inverseRadius, nz = (pz - cz) * inverseRadius;
    front = dx * nx + dy * ny + dz * nz < 0.0f;
    nx = front ? nx : -nx;
    ny = front ? ny : -ny;
    nz = front ? nz : -nz;
}

// GCC resolves a function's clones in the file that defines them: the
// exported functions below call these.
RAYCACHE_WIDE_LANE_CLONES
void sphereSurfaceLanes(const SphereHitLanes& hits, int count, SurfacePoint* out) {
    FloatLanes px, py, pz, nx, ny, nz, cx, cy, cz, radius;
    FloatMask front;
    loadLanes(hits.centerX, cx);
    loadLanes(hits.centerY, cy);
    loadLanes(hits.centerZ, cz);
    loadLanes(hits.radius, radius);
    sphereSurfaceCore(hits, cx, cy, cz, 1.0f / radius, px, py, pz, nx, ny, nz, front);
    for (int k = 0; k < count; ++k) {
        SurfacePoint& sp = out[k];
        sp.position = {px[k], py[k], pz[k]};
        sp.normal = sp.geometricNormal = {nx[k], ny[k], nz[k]};
        sp.u = sp.v = 0.0f;
        sp.frontFace = laneSet(front, k);
    }
}

// Lanes that are set where the ints are non-zero.
// (Whole-vector operations: GCC turns a loop over a vector's lanes into one
// scalar instruction per lane.)
[[gnu::always_inline]] inline void maskOf(const int* flags, FloatMask& mask) {
    IntLanes16 lanes;
    loadLanes(flags, lanes);
    mask = lanes != 0;
}

// Writes 1 where `value` is set and 0 where not, into the lanes of `to`
// that `selected` sets.
[[gnu::always_inline]] inline void storeSelectedFlags(const FloatMask& value, const FloatMask& selected, int* to) {
    IntLanes16 old;
    loadLanes(to, old);
    storeLanes(selected ? value & 1 : old, to);
}

// surfacePointAt's steps at triangle-mesh hits.
template <class Rays>
[[gnu::always_inline]] inline void meshSurfaceCore(const Rays& rays, const MeshHitLanes& h, FloatLanes& px,
                                                   FloatLanes& py,
                                                   FloatLanes& pz, FloatLanes& nx, FloatLanes& ny, FloatLanes& nz,
                                                   FloatLanes& gx, FloatLanes& gy, FloatLanes& gz, FloatLanes& tu,
                                                   FloatLanes& tv, FloatMask& front) {
    FloatLanes dx, dy, dz, u, v;
    hitPointLanes(rays, dx, dy, dz, px, py, pz);
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
    loadLanes(h.geometricX, gx);
    loadLanes(h.geometricY, gy);
    loadLanes(h.geometricZ, gz);
    const FloatMask flip = hasShadingNormal & (gx * sx + gy * sy + gz * sz < 0.0f);
    gx = flip ? -gx : gx;
    gy = flip ? -gy : gy;
    gz = flip ? -gz : gz;
    nx = hasShadingNormal ? sx : gx, ny = hasShadingNormal ? sy : gy, nz = hasShadingNormal ? sz : gz;
    // Texture coordinates, where the mesh has them.
    interpolateLanes(h.uv0U, h.uv1U, h.uv2U, w, u, v, tu);
    interpolateLanes(h.uv0V, h.uv1V, h.uv2V, w, u, v, tv);
    FloatMask hasUvs;
    maskOf(h.hasUvs, hasUvs);
    tu = hasUvs ? tu : FloatLanes{};
    tv = hasUvs ? tv : FloatLanes{};
    // Turned toward the ray (faceToward).
    front = dx * gx + dy * gy + dz * gz < 0.0f;
    nx = front ? nx : -nx, ny = front ? ny : -ny, nz = front ? nz : -nz;
    gx = front ? gx : -gx, gy = front ? gy : -gy, gz = front ? gz : -gz;
}

RAYCACHE_WIDE_LANE_CLONES
void meshSurfaceLanes(const MeshHitLanes& h, int count, SurfacePoint* out) {
    FloatLanes px, py, pz, nx, ny, nz, gx, gy, gz, tu, tv;
    FloatMask front;
    meshSurfaceCore(h, h, px, py, pz, nx, ny, nz, gx, gy, gz, tu, tv, front);
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

// One light seen from surface points (LocalShading::shadowQueries): the
// direction toward it, its distance and spot factor, and the lanes it reaches.
[[gnu::always_inline]] inline void lightCore(const Light& light, const SpotCone& spot, const FloatLanes& px,
                                             const FloatLanes& py, const FloatLanes& pz, const FloatLanes& nx,
                                             const FloatLanes& ny, const FloatLanes& nz, const FloatLanes& gx,
                                             const FloatLanes& gy, const FloatLanes& gz, FloatLanes& toX,
                                             FloatLanes& toY, FloatLanes& toZ, FloatLanes& distance,
                                             FloatLanes& strength, FloatMask& reaches) {
    strength = FloatLanes{} + 1.0f;
    if (light.type == LightType::Directional) {
        toX = -(FloatLanes{} + light.direction.x);  // negated, not 0 - x: a zero keeps its sign flipped
        toY = -(FloatLanes{} + light.direction.y);
        toZ = -(FloatLanes{} + light.direction.z);
        distance = FloatLanes{} + std::numeric_limits<float>::infinity();
    } else {
        const FloatLanes ddx = light.position.x - px, ddy = light.position.y - py, ddz = light.position.z - pz;
        const FloatLanes squared = ddx * ddx + ddy * ddy + ddz * ddz;
        FloatLanes root;
        sqrtLanes(squared, root);
        const FloatLanes inverseDistance = 1.0f / root;
        distance = squared * inverseDistance;
        toX = ddx * inverseDistance;
        toY = ddy * inverseDistance;
        toZ = ddz * inverseDistance;
        if (light.type == LightType::Spot) {
            // dot(-toLight, light.direction)
            const FloatLanes cosine = -toX * light.direction.x + -toY * light.direction.y + -toZ * light.direction.z;
            smoothstepLanes(spot.outer, spot.inner, cosine, strength);
        }
    }
    // Lights below the geometric surface would leak through interpolated normals.
    const FloatLanes shadingCosine = nx * toX + ny * toY + nz * toZ;
    const FloatLanes geometricCosine = gx * toX + gy * toY + gz * toZ;
    // Written as the scalar test's negation, so NaN lanes go the same way.
    reaches = ~((strength <= 0.0f) | (shadingCosine <= 0.0f) | (geometricCosine <= 0.0f));
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
    for (int l = 0; l < lightCount; ++l)
        lightCore(lights[static_cast<std::size_t>(l)], spot[static_cast<std::size_t>(l)], px, py, pz, nx, ny, nz, gx, gy,
                  gz, toX[l], toY[l], toZ[l], distance[l], strength[l], reaches[l]);
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

// Writes `value` into the lanes of `to` that `selected` sets.
[[gnu::always_inline]] inline void storeSelected(const FloatLanes& value, const FloatMask& selected, float* to) {
    FloatLanes old;
    loadLanes(to, old);
    storeLanes(selected ? value : old, to);
}

[[gnu::always_inline]] inline void storeSurfaceLanes(const FloatMask& selected, const FloatLanes& px,
                                                     const FloatLanes& py, const FloatLanes& pz, const FloatLanes& nx,
                                                     const FloatLanes& ny, const FloatLanes& nz, const FloatLanes& gx,
                                                     const FloatLanes& gy, const FloatLanes& gz, const FloatLanes& tu,
                                                     const FloatLanes& tv, const FloatMask& front,
                                                     SurfaceLanes16& out) {
    storeSelected(px, selected, out.positionX);
    storeSelected(py, selected, out.positionY);
    storeSelected(pz, selected, out.positionZ);
    storeSelected(nx, selected, out.normalX);
    storeSelected(ny, selected, out.normalY);
    storeSelected(nz, selected, out.normalZ);
    storeSelected(gx, selected, out.geometricX);
    storeSelected(gy, selected, out.geometricY);
    storeSelected(gz, selected, out.geometricZ);
    storeSelected(tu, selected, out.u);
    storeSelected(tv, selected, out.v);
    storeSelectedFlags(front, selected, out.frontFace);
}

RAYCACHE_WIDE_LANE_CLONES
void sphereSurfaceLanesSoa(const RayLanes16& rays, const Sphere& sphere, const int* lanes, SurfaceLanes16& out) {
    FloatLanes px, py, pz, nx, ny, nz;
    FloatMask front, selected;
    sphereSurfaceCore(rays, FloatLanes{} + sphere.center.x, FloatLanes{} + sphere.center.y,
                      FloatLanes{} + sphere.center.z, FloatLanes{} + 1.0f / sphere.radius, px, py, pz, nx, ny, nz,
                      front);
    maskOf(lanes, selected);
    storeSurfaceLanes(selected, px, py, pz, nx, ny, nz, nx, ny, nz, FloatLanes{}, FloatLanes{}, front, out);
}

RAYCACHE_WIDE_LANE_CLONES
void meshSurfaceLanesSoa(const RayLanes16& rays, const MeshHitLanes& hits, const int* lanes, SurfaceLanes16& out) {
    FloatLanes px, py, pz, nx, ny, nz, gx, gy, gz, tu, tv;
    FloatMask front, selected;
    meshSurfaceCore(rays, hits, px, py, pz, nx, ny, nz, gx, gy, gz, tu, tv, front);
    maskOf(lanes, selected);
    storeSurfaceLanes(selected, px, py, pz, nx, ny, nz, gx, gy, gz, tu, tv, front, out);
}

[[gnu::always_inline]] inline void loadSurface(const SurfaceLanes16& s, FloatLanes& px, FloatLanes& py, FloatLanes& pz,
                                               FloatLanes& nx, FloatLanes& ny, FloatLanes& nz) {
    loadLanes(s.positionX, px);
    loadLanes(s.positionY, py);
    loadLanes(s.positionZ, pz);
    loadLanes(s.normalX, nx);
    loadLanes(s.normalY, ny);
    loadLanes(s.normalZ, nz);
}

RAYCACHE_WIDE_LANE_CLONES
void shadowRayLanesSoa(const Light& light, const SpotCone& spot, const SurfaceLanes16& surfaces, const int* lanes,
                       RayLanes16& rays, PacketLanes& traced, LightLanes16& seen) {
    FloatLanes px, py, pz, nx, ny, nz, gx, gy, gz;
    loadSurface(surfaces, px, py, pz, nx, ny, nz);
    loadLanes(surfaces.geometricX, gx);
    loadLanes(surfaces.geometricY, gy);
    loadLanes(surfaces.geometricZ, gz);
    FloatLanes offset;
    surfaceOffsetLanes(px, py, pz, offset);
    FloatLanes toX, toY, toZ, distance, strength;
    FloatMask reaches, selected;
    lightCore(light, spot, px, py, pz, nx, ny, nz, gx, gy, gz, toX, toY, toZ, distance, strength, reaches);
    maskOf(lanes, selected);
    reaches &= selected;
    storeLanes(px + gx * offset, rays.originX);
    storeLanes(py + gy * offset, rays.originY);
    storeLanes(pz + gz * offset, rays.originZ);
    storeLanes(toX, rays.directionX);
    storeLanes(toY, rays.directionY);
    storeLanes(toZ, rays.directionZ);
    storeLanes(FloatLanes{}, rays.tNear);
    storeLanes(FloatLanes{}, rays.time);
    storeLanes(distance, rays.tFar);
    for (int k = 0; k < kFloatLanes; ++k) {
        rays.mask[k] = 0xFFFFFFFFu;
        rays.id[k] = 0;
        rays.flags[k] = 0;
    }
    storeLanes(reaches, traced.valid);
    storeLanes(toX, seen.toX);
    storeLanes(toY, seen.toY);
    storeLanes(toZ, seen.toZ);
    storeLanes(strength, seen.strength);
}

// specularPower (render/SpecularPower.h) of sixteen cosines, one exponent.
[[gnu::always_inline]] inline void specularPowerLanes(const FloatLanes& x, float shininess, FloatLanes& out) {
    const bool whole = shininess >= 0.0f && shininess <= 65535.0f &&
                       static_cast<float>(static_cast<int>(shininess)) == shininess;
    if (!whole) {
        for (int k = 0; k < kFloatLanes; ++k) out[k] = specularPower(x[k], shininess);
        return;
    }
    auto exponent = static_cast<unsigned>(shininess);
    FloatLanes result = FloatLanes{} + 1.0f, base = x;
    while (exponent != 0) {
        if (exponent & 1u) result *= base;
        exponent >>= 1;
        if (exponent != 0) base *= base;
    }
    out = result;
}

RAYCACHE_WIDE_LANE_CLONES
void directLightLanesSoa(const Material& material, std::span<const Light> lights, const LightLanes16* seen,
                         const SurfaceLanes16& surfaces, const RayLanes16& viewRays, const int* lanes, float* outR,
                         float* outG, float* outB) {
    FloatLanes albedoR, albedoG, albedoB, nx, ny, nz;
    loadLanes(surfaces.albedoR, albedoR);
    loadLanes(surfaces.albedoG, albedoG);
    loadLanes(surfaces.albedoB, albedoB);
    loadLanes(surfaces.normalX, nx);
    loadLanes(surfaces.normalY, ny);
    loadLanes(surfaces.normalZ, nz);
    // LocalShading::directLight's steps, in its order.
    FloatLanes colorR = material.ambient.r * albedoR, colorG = material.ambient.g * albedoG,
               colorB = material.ambient.b * albedoB;
    const bool highlights = !material.specular.isBlack();
    FloatLanes viewX, viewY, viewZ;
    if (highlights) {
        loadLanes(viewRays.directionX, viewX);
        loadLanes(viewRays.directionY, viewY);
        loadLanes(viewRays.directionZ, viewZ);
        viewX = -viewX, viewY = -viewY, viewZ = -viewZ;
    }
    for (std::size_t l = 0; l < lights.size(); ++l) {
        const LightLanes16& light = seen[l];
        FloatMask lit;
        maskOf(light.lit, lit);
        if (!anyLane(lit)) continue;
        FloatLanes toX, toY, toZ, strength;
        loadLanes(light.toX, toX);
        loadLanes(light.toY, toY);
        loadLanes(light.toZ, toZ);
        loadLanes(light.strength, strength);
        const FloatLanes cosine = nx * toX + ny * toY + nz * toZ;
        FloatLanes litR = albedoR * cosine, litG = albedoG * cosine, litB = albedoB * cosine;
        if (highlights) {
            const FloatLanes hx = toX + viewX, hy = toY + viewY, hz = toZ + viewZ;
            FloatLanes root;
            sqrtLanes(hx * hx + hy * hy + hz * hz, root);
            const FloatLanes inverse = 1.0f / root;
            const FloatLanes cosineH = nx * (hx * inverse) + ny * (hy * inverse) + nz * (hz * inverse);
            const FloatLanes nDotH = 0.0f < cosineH ? cosineH : FloatLanes{};  // std::max(0.0f, cosineH)
            FloatLanes power;
            specularPowerLanes(nDotH, material.shininess, power);
            litR = litR + material.specular.r * power;
            litG = litG + material.specular.g * power;
            litB = litB + material.specular.b * power;
        }
        const Rgb& intensity = lights[l].intensity;
        colorR = lit ? colorR + litR * intensity.r * strength : colorR;
        colorG = lit ? colorG + litG * intensity.g * strength : colorG;
        colorB = lit ? colorB + litB * intensity.b * strength : colorB;
    }
    FloatMask selected;
    maskOf(lanes, selected);
    storeSelected(colorR, selected, outR);
    storeSelected(colorG, selected, outG);
    storeSelected(colorB, selected, outB);
}

RAYCACHE_WIDE_LANE_CLONES
void secondaryRayLanesSoa(const Material& material, float curvature, float minWeight, const SurfaceLanes16& surfaces,
                          const RayLanes16& rays, const float* pathWeights, const float* coneWidth,
                          const float* coneSpread, const int* lanes, SecondaryRayLanes16& out) {
    FloatLanes px, py, pz, nx, ny, nz, gx, gy, gz, dx, dy, dz, t, pathWeight, width0, spread0;
    loadSurface(surfaces, px, py, pz, nx, ny, nz);
    loadLanes(surfaces.geometricX, gx);
    loadLanes(surfaces.geometricY, gy);
    loadLanes(surfaces.geometricZ, gz);
    loadLanes(rays.directionX, dx);
    loadLanes(rays.directionY, dy);
    loadLanes(rays.directionZ, dz);
    loadLanes(rays.tFar, t);
    loadLanes(pathWeights, pathWeight);
    loadLanes(coneWidth, width0);
    loadLanes(coneSpread, spread0);
    FloatMask selected, front;
    maskOf(lanes, selected);
    maskOf(surfaces.frontFace, front);
    FloatLanes offset;
    surfaceOffsetLanes(px, py, pz, offset);
    // RayCone::bounced(t, curvature)
    FloatLanes width;
    absLanes(width0 + spread0 * t, width);
    storeSelected(width, selected, out.coneWidth);
    storeSelected(spread0 + 2.0f * width * curvature, selected, out.coneSpread);
    // The incident ray's cosine, as reflect() and refract() take it.
    const FloatLanes cosI = -(dx * nx + dy * ny + dz * nz);
    FloatLanes reflectWeight = FloatLanes{} + material.reflectivity;
    FloatMask refracts{};
    if (material.refracts()) {
        // Entering: air -> material; leaving: material -> air (objects do not nest).
        const FloatLanes eta = front ? FloatLanes{} + 1.0f / material.ior : FloatLanes{} + material.ior;
        const FloatLanes cos2T = 1.0f - eta * eta * (1.0f - cosI * cosI);
        const FloatMask total = cos2T < 0.0f;  // total internal reflection: the transmitted share is reflected
        FloatLanes root;
        sqrtLanes(total ? FloatLanes{} : cos2T, root);
        const FloatLanes k = eta * cosI - root;
        const FloatLanes rx = dx * eta + nx * k, ry = dy * eta + ny * k, rz = dz * eta + nz * k;
        FloatLanes length;
        sqrtLanes(rx * rx + ry * ry + rz * rz, length);
        const FloatLanes inverse = 1.0f / length;
        storeSelected(rx * inverse, selected, out.refractedX);
        storeSelected(ry * inverse, selected, out.refractedY);
        storeSelected(rz * inverse, selected, out.refractedZ);
        storeSelected(px - gx * offset, selected, out.belowX);
        storeSelected(py - gy * offset, selected, out.belowY);
        storeSelected(pz - gz * offset, selected, out.belowZ);
        refracts = ~total & (pathWeight * material.transmissivity >= minWeight);
        reflectWeight = total ? reflectWeight + material.transmissivity : reflectWeight;
    }
    const FloatMask reflects = (reflectWeight > 0.0f) & (pathWeight * reflectWeight >= minWeight);
    // normalize(reflect(d, n))
    const FloatLanes twice = 2.0f * cosI;
    const FloatLanes rx = dx + nx * twice, ry = dy + ny * twice, rz = dz + nz * twice;
    FloatLanes length;
    sqrtLanes(rx * rx + ry * ry + rz * rz, length);
    const FloatLanes inverse = 1.0f / length;
    storeSelected(rx * inverse, selected, out.reflectedX);
    storeSelected(ry * inverse, selected, out.reflectedY);
    storeSelected(rz * inverse, selected, out.reflectedZ);
    storeSelected(px + gx * offset, selected, out.aboveX);
    storeSelected(py + gy * offset, selected, out.aboveY);
    storeSelected(pz + gz * offset, selected, out.aboveZ);
    storeSelected(reflectWeight, selected, out.reflectWeight);
    storeSelectedFlags(reflects, selected, out.reflects);
    storeSelectedFlags(refracts, selected, out.refracts);
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

void sphereSurfaceLanes16(const RayLanes16& rays, const Sphere& sphere, const int* lanes, SurfaceLanes16& out) {
    sphereSurfaceLanesSoa(rays, sphere, lanes, out);
}

void meshSurfaceLanes16(const RayLanes16& rays, const MeshHitLanes& triangles, const int* lanes,
                        SurfaceLanes16& out) {
    meshSurfaceLanesSoa(rays, triangles, lanes, out);
}

void shadowRayLanes16(const Light& light, const SpotCone& spot, const SurfaceLanes16& surfaces, const int* lanes,
                      RayLanes16& rays, PacketLanes& traced, LightLanes16& seen) {
    shadowRayLanesSoa(light, spot, surfaces, lanes, rays, traced, seen);
}

void directLightLanes16(const Material& material, std::span<const Light> lights, const LightLanes16* seen,
                        const SurfaceLanes16& surfaces, const RayLanes16& viewRays, const int* lanes, float* outR,
                        float* outG, float* outB) {
    directLightLanesSoa(material, lights, seen, surfaces, viewRays, lanes, outR, outG, outB);
}

void secondaryRayLanes16(const Material& material, float curvature, float minWeight, const SurfaceLanes16& surfaces,
                         const RayLanes16& rays, const float* pathWeight, const float* coneWidth,
                         const float* coneSpread, const int* lanes, SecondaryRayLanes16& out) {
    secondaryRayLanesSoa(material, curvature, minWeight, surfaces, rays, pathWeight, coneWidth, coneSpread, lanes,
                         out);
}

}  // namespace raycache
